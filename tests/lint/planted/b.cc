namespace simtree {
#ifdef PLANT_CLASH
struct Planted {  // the same name, another type
  double weight = 0.0;
};
#else
struct Planted {
  int count = 0;
  double weight = 0.0;
};
#endif
}  // namespace simtree

double WeightB(const simtree::Planted& p) { return p.weight; }
