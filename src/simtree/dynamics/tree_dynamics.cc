#include "simtree/dynamics/tree_dynamics.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"
#include "simtree/dynamics/detail/branch_mechanics.h"
#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"
#include "simtree/dynamics/detail/loads.h"
#include "simtree/dynamics/detail/modal_step.h"
#include "simtree/dynamics/detail/node_deform.h"
#include "simtree/dynamics/detail/pose.h"
#include "simtree/dynamics/detail/ropes.h"
#include "simtree/dynamics/detail/scheduler.h"

namespace simtree::dynamics {
namespace {

void CheckMaterialForSimulation(const Material& m, const std::string& source,
                                const std::string& at) {
  for (int i = 0; i < 3; ++i) {
    const Mode& mode = m.modes[i];
    const std::string where = fmt::format("{}.modes[{}]", at, i);
    if (!std::isfinite(mode.frequency_hz) || mode.frequency_hz <= 0.0) {
      throw InputError(source, where + ".frequency_hz",
                       fmt::format("expected a positive finite natural frequency (Hz), got {}",
                                   mode.frequency_hz));
    }
    if (!std::isfinite(mode.damping_ratio) || mode.damping_ratio < 0.0) {
      throw InputError(
          source, where + ".damping_ratio",
          fmt::format("expected a finite damping ratio >= 0, got {}", mode.damping_ratio));
    }
  }
  if (!std::isfinite(m.mass_kg) || m.mass_kg <= 0.0) {
    throw InputError(source, at + ".mass_kg",
                     fmt::format("expected a positive finite modal mass (kg), got {}", m.mass_kg));
  }
  if (!std::isfinite(m.stiffness) || m.stiffness <= 0.0) {
    throw InputError(
        source, at + ".stiffness",
        fmt::format("expected a positive finite stiffness (N/m), got {}", m.stiffness));
  }
}

// The authors' demo spread of a branch's three modes: {0.95 f, 1.05 f, f} and damping {1.2 zeta,
// 0.8 zeta, zeta}, f and zeta those of the twist mode.
void SpreadModesAsTheDemo(Tree& tree) {
  for (Branch& b : tree.branches) {
    Material& m = *b.material;
    const double f = m.modes[kModeT].frequency_hz, z = m.modes[kModeT].damping_ratio;
    m.modes[kModeW].frequency_hz = 1.05 * f;
    m.modes[kModeW].damping_ratio = 0.8 * z;
    m.modes[kModeU].damping_ratio = 1.2 * z;
    m.SetFrequency(ModeKind::kBendU, 0.95 * f);
  }
}

// The tree as the model simulates it: checked, with the demo spread when asked for.
Tree TreeToSimulate(const Tree& input, const DynamicsOptions& options) {
  ValidateForSimulation(input, "tree");
  Tree tree = input;
  if (options.demo_mode_spread) SpreadModesAsTheDemo(tree);
  return tree;
}

const DynamicsOptions& Validated(const DynamicsOptions& options) {
  options.Validate();
  return options;
}

}  // namespace

void DynamicsOptions::Validate() const {
  const std::string source = "dynamics options";
  CheckOption(
      integrator == Integrator::kExact || integrator == Integrator::kSemiImplicitEuler ||
          integrator == Integrator::kExplicitEuler,
      source, "integrator",
      fmt::format("expected one of the Integrator values, got {}", static_cast<int>(integrator)));
  CheckOption(std::isfinite(twist_stiffness_ratio) && twist_stiffness_ratio > 0.0, source,
              "twist_stiffness_ratio",
              fmt::format("expected a positive ratio, got {}", twist_stiffness_ratio));
  CheckOption(max_threads >= 0, source, "max_threads",
              fmt::format("expected 0 (all cores) or more, got {}", max_threads));
  wind.Validate();
}

void ValidateForSimulation(const Tree& tree, const std::string& source) {
  if (tree.empty()) throw InputError(source, "branches", "expected at least one branch");
  for (const Branch& b : tree.branches) {
    const std::string at = fmt::format("branches[{}].material", b.id);
    if (!b.material) {
      throw InputError(source, at,
                       "expected a material (frequency, damping, stiffness) on every branch: "
                       "measure them with a pull test (simtree identify, then simtree build "
                       "--materials), assume typical ones without one (simtree build --species "
                       "NAME), or give a parameter file (--material-file)");
    }
    CheckMaterialForSimulation(*b.material, source, at);
  }
  ValidationOptions options;
  options.require_materials = true;
  Validate(tree, source, options);
}

// ------------------------------------------------------------------------------------------------

// The model's constants and state, and the orchestration of a step: loads, then every branch
// advanced, posed and deformed, parents before children.
struct TreeDynamics::Impl {
  DynamicsOptions options;
  DynamicsModel model;
  BranchScheduler scheduler;
  std::vector<BranchState> state;
  LoadTable loads;
  std::vector<Eigen::Vector3f> positions;
  std::map<int, RopeSlot> ropes;
  int next_rope_id = 0;
  WindField wind;
  Eigen::Vector3d bounds_min, bounds_max;
  double step_dt = 0;  // dt the oscillator steps are for (0 = none yet)
  double time = 0;
  int64_t steps = 0;

  Impl(const Tree& input, const DynamicsOptions& opts)
      : options(Validated(opts)),
        model(BuildDynamicsModel(TreeToSimulate(input, options))),
        scheduler(options.max_threads) {
    for (int b = 0; b < size(); ++b) UpdateMechanics(b);
    state.resize(size());
    loads.load.resize(size());
    positions.assign(model.tree.NodeCount(), Eigen::Vector3f::Zero());
    model.tree.Bounds(&bounds_min, &bounds_max);
    wind = WindField(options.wind, bounds_min, bounds_max);
    ResetState();
  }

  int size() const { return model.size(); }
  const BranchState* ParentState(int id) const {
    const int parent = model.links[id].parent;
    return parent >= 0 ? &state[parent] : nullptr;
  }
  Eigen::Vector3d PointNow(int id, double arc_length) const {
    return dynamics::PointNow(model, state[id], id, arc_length);
  }

  // After a material change (and at the start): the branch's mechanics and oscillator steps.
  void UpdateMechanics(int id) {
    BranchModel& m = model.models[id];
    BranchLink& k = model.links[id];
    SetBranchMechanics(ComputeBranchMechanics(model.tree.branches[id], m, k, model.nodes,
                                              options.twist_stiffness_ratio),
                       m, k);
    if (step_dt > 0.0) SetSteps(id);
  }

  // The branch's oscillator steps and bank share for the step length step_dt.
  void SetSteps(int id) {
    BranchLink& k = model.links[id];
    k.step = MakeBranchSteps(model.models[id].mechanics, step_dt, options.integrator);
    k.bank_keep = SwingBankKeep(model.models[id].mechanics, step_dt);
  }

  std::span<const int> Children(int id) const {
    const TreeOrder& o = model.order;
    return {o.child_list.data() + o.child_begin[id],
            static_cast<size_t>(o.child_begin[id + 1] - o.child_begin[id])};
  }

  void UpdateGeometry() {
    scheduler.TopDown(model.order, [&](int id) {
      PoseBranch(model.links[id], model.models[id], ParentState(id), state[id]);
      DeformNodes(model.nodes, model.links[id], state[id], positions.data());
    });
  }

  bool DistributedLoads() const { return options.gravity || wind.options().enabled; }
  bool AnyLoad() const { return DistributedLoads() || !ropes.empty(); }

  // Weight and wind on every branch, the ropes on theirs, and (with load transfer) every
  // branch's reaction gathered by its parent, children first.
  void ComputeDistributedLoads() {
    if (wind.options().enabled) wind.SampleGrid(time);
    scheduler.ForRange(0, size(), [&](int id) {
      loads.load[id] =
          OwnDistributedLoad(model.models[id].mechanics, state[id], options.gravity, wind);
    });
    loads.all_loaded = true;
    for (const auto& [rope_id, slot] : ropes) {
      const int b = slot.rope.branch;
      const PointOnBranch p = PointAt(model.tree.branches[b], model.models[b], slot.arc_length);
      AddPointLoad(state[b].frame, p.phi, p.slope, p.psi, state[b].frame * p.rest_offset,
                   RopeForce(model, state, slot), Eigen::Vector3d::Zero(), loads.load[b]);
    }
    if (!options.transfer_loads) return;
    const TreeOrder& order = model.order;
    scheduler.ParentsBottomUp(order, [&](int parent) {
      for (int c = order.child_begin[parent]; c < order.child_begin[parent + 1]; ++c) {
        const int child = order.child_list[c];
        AddChildReaction(model.links[child], state[parent].frame, loads.load[child].force,
                         loads.load[child].moment, loads.load[parent]);
      }
    });
  }

  // Fills `loads` for the configuration now. Ropes alone touch only their branches' chains.
  void ComputeLoads() {
    loads.Clear();
    if (DistributedLoads()) {
      ComputeDistributedLoads();
      return;
    }
    for (const auto& [rope_id, slot] : ropes) {
      WalkPointLoad(model, state, options.transfer_loads,
                    {slot.rope.branch, slot.arc_length, RopeForce(model, state, slot)}, loads.load,
                    &loads.loaded);
    }
  }

  void Step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      throw InputError("TreeDynamics::Step", "dt",
                       fmt::format("expected a positive finite time step (s), got {}", dt));
    }
    if (dt != step_dt) {
      step_dt = dt;
      scheduler.ForRange(0, size(), [&](int id) { SetSteps(id); });
    }
    const bool loaded_step = AnyLoad();
    if (loaded_step) {
      ComputeLoads();
    } else if (loads.all_loaded || !loads.loaded.empty()) {
      loads.Clear();
    }
    // One pass, parents before children: a branch (advanced by its parent, or first of all for a
    // trunk) is posed on its parent and deformed, then advances its children.
    const std::span<const Load> step_loads =
        loaded_step ? std::span<const Load>(loads.load) : std::span<const Load>();
    const TreeOrder& order = model.order;
    for (int i = order.level_begin[0]; i < order.level_begin[1]; ++i) {
      const int root = order.level_order[i];
      AdvanceRoot(model.links[root],
                  loaded_step ? loads.load[root].q : std::array<double, 3>{0, 0, 0}, dt,
                  state[root]);
    }
    scheduler.TopDown(model.order, [&](int id) {
      PoseBranch(model.links[id], model.models[id], ParentState(id), state[id]);
      DeformNodes(model.nodes, model.links[id], state[id], positions.data());
      AdvanceChildren(id, Children(id), model.links, step_loads, dt, options.base_excitation,
                      state);
    });
    time += dt;
    ++steps;
  }

  void SettleStatic() {
    // Loads depend on the configuration (rope direction, frames), so iterate a few times.
    for (int iteration = 0; iteration < 4; ++iteration) {
      ComputeLoads();
      scheduler.ForRange(0, size(), [&](int id) {
        BranchState& st = state[id];
        st.modal.q = StaticDeflection(model.models[id].mechanics, loads.load[id].q);
        st.modal.v = {0, 0, 0};
        st.acceleration = {0, 0, 0};
        st.primary = st.modal;
        st.swing = ModalState{};
        st.base_acceleration.setZero();
        st.base_angular_acceleration.setZero();
        st.swing_budget = st.swing_bank = 0.0;
      });
      UpdateGeometry();
    }
  }

  void ResetState() {
    for (BranchState& st : state) st = BranchState{};
    ropes.clear();
    loads.Clear(/*everything=*/true);
    time = 0.0;
    steps = 0;
    UpdateGeometry();
    if (options.gravity) {
      // Pre-sag: the equilibrium under self-weight alone, whatever the wind does.
      const WindOptions saved = wind.options();
      if (saved.enabled) {
        WindOptions off = saved;
        off.enabled = false;
        wind = WindField(off, bounds_min, bounds_max);
      }
      SettleStatic();
      if (saved.enabled) wind = WindField(saved, bounds_min, bounds_max);
    }
  }

  void SetTension(RopeSlot& slot) const {
    slot.tension = dynamics::RopeTension(model, state, options.transfer_loads, slot);
  }
};

// ------------------------------------------------------------------------------------------------

TreeDynamics::TreeDynamics(const Tree& tree, const DynamicsOptions& options)
    : impl_(std::make_unique<Impl>(tree, options)) {}
TreeDynamics::~TreeDynamics() = default;
TreeDynamics::TreeDynamics(TreeDynamics&&) noexcept = default;
TreeDynamics& TreeDynamics::operator=(TreeDynamics&&) noexcept = default;

const Tree& TreeDynamics::tree() const { return impl_->model.tree; }
const DynamicsOptions& TreeDynamics::options() const { return impl_->options; }

void TreeDynamics::Step(double dt) { impl_->Step(dt); }

void TreeDynamics::Advance(double duration, double max_dt) {
  if (!(duration >= 0.0) || !std::isfinite(duration) || !(max_dt > 0.0)) {
    throw InputError(
        "TreeDynamics::Advance", "duration",
        fmt::format("expected a duration >= 0 and a step > 0, got {} and {}", duration, max_dt));
  }
  if (duration == 0.0) return;
  const int64_t n = static_cast<int64_t>(std::ceil(duration / max_dt - 1e-9));
  const double dt = duration / static_cast<double>(n);
  for (int64_t i = 0; i < n; ++i) impl_->Step(dt);
}

double TreeDynamics::time() const { return impl_->time; }
int64_t TreeDynamics::steps() const { return impl_->steps; }
void TreeDynamics::Reset() { impl_->ResetState(); }
void TreeDynamics::SettleStatic() { impl_->SettleStatic(); }

int TreeDynamics::AttachRope(const Rope& rope) {
  RopeSlot slot;
  slot.rope = rope;
  slot.arc_length = ValidateRope(impl_->model.tree, rope);
  impl_->SetTension(slot);
  const int id = impl_->next_rope_id++;
  impl_->ropes[id] = slot;
  return id;
}

void TreeDynamics::UpdateRope(int id, const Rope& rope) {
  auto it = impl_->ropes.find(id);
  if (it == impl_->ropes.end()) {
    throw InputError("rope", "id", fmt::format("expected an attached rope, got id {}", id));
  }
  RopeSlot slot;
  slot.rope = rope;
  slot.arc_length = ValidateRope(impl_->model.tree, rope);
  impl_->SetTension(slot);
  it->second = slot;
}

void TreeDynamics::ReleaseRope(int id) { impl_->ropes.erase(id); }
void TreeDynamics::ReleaseAllRopes() { impl_->ropes.clear(); }
bool TreeDynamics::HasRope(int id) const { return impl_->ropes.count(id) > 0; }

const Rope& TreeDynamics::rope(int id) const {
  auto it = impl_->ropes.find(id);
  if (it == impl_->ropes.end()) {
    throw InputError("rope", "id", fmt::format("expected an attached rope, got id {}", id));
  }
  return it->second.rope;
}

double TreeDynamics::RopeTension(int id) const {
  auto it = impl_->ropes.find(id);
  return it == impl_->ropes.end() ? 0.0 : it->second.tension;
}

Eigen::Vector3d TreeDynamics::RopePoint(int id) const {
  auto it = impl_->ropes.find(id);
  if (it == impl_->ropes.end()) {
    throw InputError("rope", "id", fmt::format("expected an attached rope, got id {}", id));
  }
  return impl_->PointNow(it->second.rope.branch, it->second.arc_length);
}

void TreeDynamics::SetWind(const WindOptions& wind) {
  impl_->wind = WindField(wind, impl_->bounds_min, impl_->bounds_max);
  impl_->options.wind = wind;
}

void TreeDynamics::SetWindEnabled(bool enabled) {
  WindOptions w = impl_->options.wind;
  w.enabled = enabled;
  SetWind(w);
}

void TreeDynamics::SetWindSpeed(double mean_speed_mps) {
  WindOptions w = impl_->options.wind;
  w.mean_speed_mps = mean_speed_mps;
  SetWind(w);
}

const WindOptions& TreeDynamics::wind() const { return impl_->options.wind; }

Eigen::Vector3d TreeDynamics::WindVelocity(const Eigen::Vector3d& point) const {
  return impl_->wind.VelocityExact(point, impl_->time);
}

const Material& TreeDynamics::material(int branch) const {
  return *impl_->model.tree.branches.at(branch).material;
}

void TreeDynamics::SetMaterial(int branch, const Material& material) {
  if (branch < 0 || branch >= impl_->size()) {
    throw InputError(
        "material", "branch",
        fmt::format("expected a branch id in [0, {}], got {}", impl_->size() - 1, branch));
  }
  CheckMaterialForSimulation(material, "material", fmt::format("branches[{}]", branch));
  impl_->model.tree.branches[branch].material = material;
  impl_->UpdateMechanics(branch);
  // Ropes pulling by displacement need the new compliance.
  for (auto& [id, slot] : impl_->ropes) impl_->SetTension(slot);
}

const ModalState& TreeDynamics::modal_state(int branch) const {
  return impl_->state.at(branch).modal;
}

void TreeDynamics::SetModalState(int branch, const ModalState& s) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(s.q[i]) || !std::isfinite(s.v[i])) {
      throw InputError("modal state", fmt::format("branch {}", branch),
                       "expected finite coordinates and rates");
    }
  }
  BranchState& st = impl_->state.at(branch);
  st.modal = st.primary = s;
  st.swing = ModalState{};
  impl_->UpdateGeometry();
}

double TreeDynamics::BranchEnergy(int branch) const {
  return ModalEnergy(impl_->model.models.at(branch).mechanics, impl_->state[branch].modal);
}

double TreeDynamics::Energy() const {
  double e = 0.0;
  for (int b = 0; b < impl_->size(); ++b) e += BranchEnergy(b);
  return e;
}

std::span<const Eigen::Vector3f> TreeDynamics::node_positions() const { return impl_->positions; }
int TreeDynamics::node_offset(int branch) const { return impl_->model.links.at(branch).first_node; }
int TreeDynamics::node_count() const { return static_cast<int>(impl_->positions.size()); }
int TreeDynamics::branch_count() const { return impl_->size(); }

BranchPose TreeDynamics::pose(int branch) const {
  const BranchState& st = impl_->state.at(branch);
  BranchPose p;
  p.origin = st.origin;
  p.rotation = st.frame * impl_->model.models[branch].frame.transpose();
  p.frame.u = st.frame.col(0);
  p.frame.v = st.frame.col(1);
  p.frame.w = st.frame.col(2);
  return p;
}

Eigen::Vector3d TreeDynamics::PointPosition(int branch, double arc_length) const {
  if (branch < 0 || branch >= impl_->size()) {
    throw InputError(
        "point", "branch",
        fmt::format("expected a branch id in [0, {}], got {}", impl_->size() - 1, branch));
  }
  return impl_->PointNow(branch, arc_length);
}

Eigen::Matrix3d TreeDynamics::NodeRotation(int branch, int node) const {
  const BranchLink& k = impl_->model.links.at(branch);
  if (node < 0 || node >= k.nodes) {
    throw InputError("node rotation", fmt::format("branch {}", branch),
                     fmt::format("expected a node index in [0, {}], got {}", k.nodes - 1, node));
  }
  return dynamics::NodeRotation(impl_->model, impl_->state[branch], branch, node);
}

void TreeDynamics::NodeRotations(std::span<Eigen::Quaternionf> out) const {
  if (static_cast<int>(out.size()) != node_count()) {
    throw InputError(
        "node rotations", "out",
        fmt::format("expected room for {} rotations, got {}", node_count(), out.size()));
  }
  impl_->scheduler.ForRange(0, impl_->size(), [&](int b) {
    const BranchLink& k = impl_->model.links[b];
    for (int j = 0; j < k.nodes; ++j) {
      out[k.first_node + j] = Eigen::Quaternionf(
          dynamics::NodeRotation(impl_->model, impl_->state[b], b, j).cast<float>());
    }
  });
}

}  // namespace simtree::dynamics
