#pragma once
// `simtree eval`: every stage scored against ground truth (a synth capture's gt/, or the tree a
// stand-in scan was sampled from), with the paper's own metrics where it has them. One header per
// stage's scores; this front header gathers them.
//
//   // A whole run (`simtree eval RESULT --gt CAPTURE`): every stage and the simulated chain.
//   const simtree::eval::RunEvaluation evaluation = simtree::eval::EvaluateRun("result/",
//   "capture/"); simtree::eval::WriteRunEvaluation(evaluation, "result/eval");  // eval.json +
//   eval.md
//
//   // One stage: e.g. a tracking against the truth (paper Table III).
//   const simtree::eval::TrackingScores scores =
//       simtree::eval::ScoreTracking(boxes, trajectories, true_boxes, true_trajectories);
//
// docs/eval.md defines every figure and the commands that print them.

#include "simtree/eval/eval_run.h"                // EvaluateRun, WriteRunEvaluation: a whole run
#include "simtree/eval/identification_metrics.h"  // ScoreLinks, ScoreBranches: paper Table IV
#include "simtree/eval/reconstruction_metrics.h"  // ScoreAgainstTruth, ScoreAgainstCloud
#include "simtree/eval/registration_metrics.h"    // ViewPoseError, PairPoseError: Tables I-II
#include "simtree/eval/tracking_metrics.h"        // ScoreTracking: paper Table III
