#include "simtree/core/legacy_format.h"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/validate.h"

namespace simtree {
namespace {

// Splits text into lines (LF or CRLF) and words, remembering 1-based line numbers for errors.
class LineReader {
 public:
  LineReader(const std::string& text, std::string source) : source_(std::move(source)) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(line);
    }
    // Trailing blank lines are not content.
    while (!lines_.empty() && lines_.back().find_first_not_of(" \t") == std::string::npos) {
      lines_.pop_back();
    }
  }

  bool AtEnd() const { return next_ >= lines_.size(); }
  int line_number() const { return static_cast<int>(next_) + 1; }

  // The next line split into words; `what` says what was expected, for the error at end of file.
  std::vector<std::string> Next(const std::string& what) {
    if (AtEnd()) Fail(line_number(), fmt::format("expected {}, got the end of the file", what));
    std::istringstream words(lines_[next_++]);
    std::vector<std::string> out;
    for (std::string w; words >> w;) out.push_back(w);
    return out;
  }

  [[noreturn]] void Fail(int line, const std::string& message) const {
    throw InputError(source_, fmt::format("line {}", line), message);
  }

  double Number(const std::string& word, int line, const std::string& what) const {
    double x = 0.0;
    const char* end = word.data() + word.size();
    auto [ptr, ec] = std::from_chars(word.data(), end, x);
    if (ec != std::errc() || ptr != end || !std::isfinite(x)) {
      Fail(line, fmt::format("expected a finite number for {}, got \"{}\"", what, word));
    }
    return x;
  }

  int Integer(const std::string& word, int line, const std::string& what) const {
    int x = 0;
    const char* end = word.data() + word.size();
    auto [ptr, ec] = std::from_chars(word.data(), end, x);
    if (ec != std::errc() || ptr != end) {
      Fail(line, fmt::format("expected an integer for {}, got \"{}\"", what, word));
    }
    return x;
  }

 private:
  std::string source_;
  std::vector<std::string> lines_;
  size_t next_ = 0;
};

// The shortest text that reads back as the same double: the demo files' numbers (written with 6
// to 8 significant digits) come back unchanged after a round trip.
std::string FormatNumber(double x) {
  if (x == 0.0) x = 0.0;  // never "-0"
  return fmt::format("{}", x);
}

Eigen::Vector3d FromDemo(const Eigen::Vector3d& p, const LegacyOptions& o) {
  const Eigen::Vector3d q = o.y_up ? Eigen::Vector3d(p.x(), -p.z(), p.y()) : p;
  return q * o.scale;
}

Eigen::Vector3d ToDemo(const Eigen::Vector3d& p, const LegacyOptions& o) {
  const Eigen::Vector3d q = p / o.scale;
  return o.y_up ? Eigen::Vector3d(q.x(), q.z(), -q.y()) : q;
}

struct LegacyBlock {
  int id = 0;
  int line = 0;                               // where the block starts, for errors
  std::vector<std::pair<int, int>> children;  // (child id, node index)
  std::vector<Node> nodes;
};

// The header "RowMax=<branches>": how many branch blocks follow.
int ReadRowMax(LineReader& in) {
  const int header_line = in.line_number();
  const std::vector<std::string> header = in.Next("the header \"RowMax=<branches>\"");
  if (header.size() != 1 || header[0].rfind("RowMax=", 0) != 0) {
    in.Fail(header_line, "expected the header \"RowMax=<number of branches>\"");
  }
  const int count = in.Integer(header[0].substr(7), header_line, "RowMax");
  if (count <= 0) in.Fail(header_line, fmt::format("expected RowMax >= 1, got {}", count));
  return count;
}

// The block's child lines "<child id> <node index>".
void ReadChildren(LineReader& in, int child_count, int node_count, int count, LegacyBlock& block) {
  const int id = block.id;
  for (int c = 0; c < child_count; ++c) {
    const int line = in.line_number();
    const auto words = in.Next(fmt::format("child {} of branch {}", c, id));
    if (words.size() != 2) {
      in.Fail(line,
              fmt::format("expected \"<child id> <node index>\" for child {} of branch {}", c, id));
    }
    const int child = in.Integer(words[0], line, "the child id");
    const int at = in.Integer(words[1], line, "the node index");
    if (child < 0 || child >= count || child == id) {
      in.Fail(line, fmt::format("child id {} of branch {} is out of range [0, {}]", child, id,
                                count - 1));
    }
    if (at < 0 || at >= node_count) {
      in.Fail(line, fmt::format("child {} of branch {} starts at node {}, but branch {} has {} "
                                "nodes (expected an index in [0, {}])",
                                child, id, at, id, node_count, node_count - 1));
    }
    block.children.emplace_back(child, at);
  }
}

// The block's node lines "x y z radius", in simtree's frame and units.
void ReadNodes(LineReader& in, int node_count, const LegacyOptions& options, LegacyBlock& block) {
  for (int n = 0; n < node_count; ++n) {
    const int line = in.line_number();
    const auto words = in.Next(fmt::format("node {} of branch {} (\"x y z radius\")", n, block.id));
    if (words.size() != 4) {
      in.Fail(line, fmt::format("expected 4 numbers \"x y z radius\" for node {} of branch {}, "
                                "got {} words",
                                n, block.id, words.size()));
    }
    Node node;
    const Eigen::Vector3d p(in.Number(words[0], line, "x"), in.Number(words[1], line, "y"),
                            in.Number(words[2], line, "z"));
    node.position = FromDemo(p, options);
    node.radius = in.Number(words[3], line, "the radius") * options.scale;
    block.nodes.push_back(node);
  }
}

// Branch block b of `count`: "<id> <nodes> <children> <colour>", then its children and nodes.
LegacyBlock ReadBlock(LineReader& in, int b, int count, const LegacyOptions& options,
                      const std::map<int, LegacyBlock>& blocks) {
  LegacyBlock block;
  block.line = in.line_number();
  const std::vector<std::string> head =
      in.Next(fmt::format("the header of branch block {} of {}", b + 1, count));
  if (head.size() != 4) {
    in.Fail(block.line, fmt::format("expected \"<id> <nodes> <children> <colour>\" for branch "
                                    "block {} of {}, got {} words",
                                    b + 1, count, head.size()));
  }
  const int id = in.Integer(head[0], block.line, "the branch id");
  const int node_count = in.Integer(head[1], block.line, "the node count");
  const int child_count = in.Integer(head[2], block.line, "the child count");
  if (id < 0 || id >= count) {
    in.Fail(block.line, fmt::format("expected a branch id in [0, {}], got {}", count - 1, id));
  }
  if (blocks.count(id)) in.Fail(block.line, fmt::format("branch id {} appears twice", id));
  if (node_count < 2) {
    in.Fail(block.line,
            fmt::format("expected at least 2 nodes for branch {}, got {}", id, node_count));
  }
  if (child_count < 0) {
    in.Fail(block.line, fmt::format("expected a child count >= 0, got {}", child_count));
  }
  block.id = id;
  ReadChildren(in, child_count, node_count, count, block);
  ReadNodes(in, node_count, options, block);
  return block;
}

// Every branch's parent (-1: none) and the node of the parent it starts at, from the child lists.
struct LegacyLinks {
  std::vector<int> parent, parent_node;
};

LegacyLinks LinkParents(const std::map<int, LegacyBlock>& blocks, int count, const LineReader& in) {
  LegacyLinks links{std::vector<int>(count, -1), std::vector<int>(count, 0)};
  for (const auto& [id, block] : blocks) {
    for (const auto& [child, at] : block.children) {
      if (links.parent[child] != -1) {
        in.Fail(block.line, fmt::format("branch {} is listed as a child of both {} and {}", child,
                                        links.parent[child], id));
      }
      links.parent[child] = id;
      links.parent_node[child] = at;
    }
  }
  return links;
}

// simtree's branch order: depth first from the trunk, or the file's own order when it lists
// every parent before its children. order[new id] = old id.
struct LegacyOrder {
  std::vector<int> order, new_id;
};

LegacyOrder BranchOrder(const std::map<int, LegacyBlock>& blocks, const LegacyLinks& links,
                        int count, const std::string& source) {
  // Exactly one branch (the trunk) has no parent.
  std::vector<int> roots;
  for (int id = 0; id < count; ++id) {
    if (links.parent[id] == -1) roots.push_back(id);
  }
  if (roots.size() != 1) {
    throw InputError(source, "",
                     fmt::format("expected exactly one trunk (a branch that is nobody's child), "
                                 "found {}",
                                 roots.size()));
  }
  LegacyOrder o{{}, std::vector<int>(count, -1)};
  std::vector<int> stack = {roots[0]};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    if (o.new_id[id] != -1) continue;
    o.new_id[id] = static_cast<int>(o.order.size());
    o.order.push_back(id);
    const auto& children = blocks.at(id).children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(it->first);
  }
  if (static_cast<int>(o.order.size()) != count) {
    throw InputError(source, "", "the child lists do not connect every branch to the trunk");
  }
  bool identity = true;
  for (int i = 0; i < count; ++i) identity = identity && links.parent[i] < i;
  if (identity) {
    o.order.clear();
    for (int i = 0; i < count; ++i) {
      o.order.push_back(i);
      o.new_id[i] = i;
    }
  }
  return o;
}

}  // namespace

std::string LegacyLevelColour(int level) {
  static const char* kColours[] = {"red", "green", "blue", "springgreen", "magenta", "orange"};
  constexpr int kCount = static_cast<int>(std::size(kColours));
  return level < kCount ? kColours[level] : "gray";
}

Tree ReadLegacyTree(const std::filesystem::path& path, const LegacyOptions& options) {
  if (!(options.scale > 0.0) || !std::isfinite(options.scale)) {
    throw InputError(path.string(), "scale",
                     fmt::format("expected a positive scale, got {}", options.scale));
  }
  const std::string source = path.string();
  LineReader in(ReadFile(path), source);
  const int count = ReadRowMax(in);
  std::map<int, LegacyBlock> blocks;
  for (int b = 0; b < count; ++b) {
    LegacyBlock block = ReadBlock(in, b, count, options, blocks);
    blocks.emplace(block.id, std::move(block));
  }
  if (!in.AtEnd()) {
    in.Fail(in.line_number(),
            fmt::format("expected the end of the file after {} branches (RowMax)", count));
  }
  const LegacyLinks links = LinkParents(blocks, count, in);
  const LegacyOrder order = BranchOrder(blocks, links, count, source);

  Tree tree;
  tree.metadata.source = fmt::format("legacy {}", path.filename().string());
  tree.branches.resize(count);
  for (int i = 0; i < count; ++i) {
    const int old = order.order[i];
    Branch& b = tree.branches[i];
    b.id = i;
    b.parent = links.parent[old] < 0 ? -1 : order.new_id[links.parent[old]];
    b.parent_node = links.parent_node[old];
    b.nodes = blocks.at(old).nodes;
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  Validate(tree, source);
  return tree;
}

std::vector<LegacyParameterLine> ParseLegacyParameters(const std::string& text,
                                                       const std::string& source) {
  LineReader in(text, source);
  const int first = in.line_number();
  const auto head = in.Next("the number of branches on the first line");
  if (head.size() != 1) in.Fail(first, "expected the number of branches alone on the first line");
  const int count = in.Integer(head[0], first, "the number of branches");
  if (count <= 0) in.Fail(first, fmt::format("expected a positive count, got {}", count));
  std::vector<LegacyParameterLine> lines;
  for (int i = 0; i < count; ++i) {
    const int line = in.line_number();
    const auto words =
        in.Next(fmt::format("{} parameter lines (one per branch) but the file "
                            "has {}: parameters of branch {}",
                            count, i, i));
    if (words.size() != 3) {
      in.Fail(line, fmt::format("expected \"frequency_hz damping_ratio stiffness\" for branch {}, "
                                "got {} words",
                                i, words.size()));
    }
    LegacyParameterLine p;
    p.frequency_hz = in.Number(words[0], line, "the frequency");
    p.damping_ratio = in.Number(words[1], line, "the damping ratio");
    p.stiffness = in.Number(words[2], line, "the stiffness");
    if (!(p.frequency_hz > 0.0)) {
      in.Fail(line, fmt::format("expected a positive frequency, got {}", p.frequency_hz));
    }
    if (p.damping_ratio < 0.0) {
      in.Fail(line, fmt::format("expected a damping ratio >= 0, got {}", p.damping_ratio));
    }
    if (!(p.stiffness > 0.0)) {
      in.Fail(line, fmt::format("expected a positive stiffness, got {}", p.stiffness));
    }
    lines.push_back(p);
  }
  if (!in.AtEnd()) {
    in.Fail(in.line_number(),
            fmt::format("expected the end of the file after {} parameter lines", count));
  }
  return lines;
}

void ReadLegacyParameters(const std::filesystem::path& path, Tree& tree) {
  const std::vector<LegacyParameterLine> lines =
      ParseLegacyParameters(ReadFile(path), path.string());
  if (static_cast<int>(lines.size()) != tree.size()) {
    throw InputError(path.string(), "line 1",
                     fmt::format("expected parameters for {} branches (the tree's), got {}",
                                 tree.size(), lines.size()));
  }
  Tree updated = tree;
  for (int i = 0; i < updated.size(); ++i) {
    updated.branches[i].material =
        Material::FromFrequencyDampingStiffness(lines[i].frequency_hz, lines[i].damping_ratio,
                                                lines[i].stiffness, MaterialSource::kDefault);
  }
  Validate(updated, path.string());
  tree = std::move(updated);
}

void WriteLegacyTree(const Tree& tree, const std::filesystem::path& path,
                     const LegacyOptions& options) {
  Validate(tree, path.string());
  const auto children = tree.Children();
  std::string out = fmt::format("RowMax={}\r\n", tree.size());
  for (const Branch& b : tree.branches) {
    out += fmt::format("{} {} {} {}\r\n", b.id, b.nodes.size(), children[b.id].size(),
                       LegacyLevelColour(b.level));
    for (int child : children[b.id]) {
      out += fmt::format("{} {}\r\n", child, tree.branches[child].parent_node);
    }
    for (const Node& n : b.nodes) {
      const Eigen::Vector3d p = ToDemo(n.position, options);
      out += fmt::format("{} {} {} {}\r\n", FormatNumber(p.x()), FormatNumber(p.y()),
                         FormatNumber(p.z()), FormatNumber(n.radius / options.scale));
    }
  }
  WriteFileAtomically(path, out);
}

void WriteLegacyParameters(const Tree& tree, const std::filesystem::path& path) {
  std::string out = fmt::format("{}\r\n", tree.size());
  for (const Branch& b : tree.branches) {
    if (!b.material) {
      throw InputError(path.string(), fmt::format("branches[{}].material", b.id),
                       "expected a material on every branch to write a parameter file");
    }
    const Material& m = *b.material;
    out += fmt::format("{} {} {}\r\n", FormatNumber(m.modes[0].frequency_hz),
                       FormatNumber(m.modes[0].damping_ratio), FormatNumber(m.stiffness));
  }
  WriteFileAtomically(path, out);
}

}  // namespace simtree
