#include "registration_pcl.h"

#include <chrono>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/ia_fpcs.h>
#include <pcl/registration/icp.h>

namespace simtree::bench {
namespace {

using Clock = std::chrono::steady_clock;

pcl::PointCloud<pcl::PointXYZ>::Ptr ToPcl(const open3d::geometry::PointCloud& cloud) {
  auto out = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  out->reserve(cloud.points_.size());
  for (const auto& p : cloud.points_) {
    out->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                 static_cast<float>(p.z())));
  }
  return out;
}

}  // namespace

registration::BaselineResult Fpcs4PcsIcp(const open3d::geometry::PointCloud& source,
                                         const open3d::geometry::PointCloud& target,
                                         const registration::BaselineOptions& options,
                                         const FpcsOptions& fpcs_options) {
  const auto start = Clock::now();
  const auto voxel = options.feature_voxel_factor * options.spacing_m;
  const auto source_pcl = ToPcl(*source.VoxelDownSample(voxel));
  const auto target_pcl = ToPcl(*target.VoxelDownSample(voxel));
  pcl::registration::FPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ> fpcs;
  fpcs.setInputSource(source_pcl);
  fpcs.setInputTarget(target_pcl);
  fpcs.setApproxOverlap(static_cast<float>(fpcs_options.approx_overlap));
  fpcs.setDelta(static_cast<float>(fpcs_options.delta_factor * options.spacing_m), false);
  fpcs.setNumberOfSamples(fpcs_options.samples);
  fpcs.setMaxComputationTime(static_cast<int>(std::ceil(fpcs_options.max_seconds)));
  fpcs.setNumberOfThreads(fpcs_options.threads);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  fpcs.align(aligned);
  registration::BaselineResult result;
  result.coarse = Eigen::Isometry3d(fpcs.getFinalTransformation().cast<double>());
  result.coarse_seconds = std::chrono::duration<double>(Clock::now() - start).count();

  const auto full_source = ToPcl(source);
  const auto full_target = ToPcl(target);
  Eigen::Matrix4f transform = result.coarse.matrix().cast<float>();
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(full_source);
  icp.setInputTarget(full_target);
  for (double factor : options.icp_distance_factors) {
    icp.setMaxCorrespondenceDistance(factor * options.spacing_m);
    icp.setMaximumIterations(options.icp_iterations);
    icp.setTransformationEpsilon(1e-8);
    icp.align(aligned, transform);
    transform = icp.getFinalTransformation();
  }
  result.target_from_source = Eigen::Isometry3d(transform.cast<double>());
  result.fitness = icp.hasConverged() ? 1.0 : 0.0;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace simtree::bench
