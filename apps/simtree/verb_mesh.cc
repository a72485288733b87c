#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/io/mesh_io.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterMesh(CLI::App& app) {
  struct Args {
    std::string input, output, parameters;
    TreeFileOptions options;
    TubeMeshOptions mesh;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "mesh",
      "Export a tree as generalized cylinders: closed tubes, PLY or OBJ, branch id per vertex");
  verb->add_option("input", args->input, "Tree file: .json or .txt")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args->output, "Mesh file: .ply (binary) or .obj")->required();
  verb->add_option("--sides", args->mesh.sides, "Vertices around each ring")
      ->capture_default_str()
      ->check(CLI::Range(3, 256));
  verb->add_flag("!--no-caps", args->mesh.caps, "Leave the tube ends open");
  AddTreeFileOptions(verb, args->options, args->parameters);
  verb->footer(Examples({
      "simtree mesh tree.json --out tree.ply",
      "simtree mesh tree01.txt --out tree01.obj --sides 16",
  }));
  verb->callback([args] {
    FinishTreeFileOptions(args->options, args->parameters);
    RefuseToOverwriteInputs(args->output, {args->input});
    const Tree tree = ReadTreeFile(args->input, args->options);
    const TriangleMesh mesh = BuildTubeMesh(tree, args->mesh);
    MeshWriteOptions write;
    write.colour_by_level_of = &tree;
    WriteMesh(mesh, args->output, write);
    spdlog::info("wrote {} ({} vertices, {} triangles, {} branches)", args->output,
                 mesh.vertex_count(), mesh.triangle_count(), tree.size());
  });
}

}  // namespace simtree::cli
