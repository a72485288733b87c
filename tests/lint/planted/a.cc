namespace simtree {
struct Planted {
  int count = 0;
  double weight = 0.0;
};
}  // namespace simtree

double WeightA(const simtree::Planted& p) { return p.weight * p.count; }
