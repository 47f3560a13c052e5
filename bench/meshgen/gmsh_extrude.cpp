// The peer of ugs-meshgen in bench/meshgen/run.sh: the gmsh SDK (Debian gmsh 4.8) extruding the same
// 2D plan into flat layers of tetrahedra, as a gmsh user would do it: merge the plan, build the
// topology of its discrete entities, extrude every surface with `numElements` layers and
// recombine = false (tetrahedra), mesh in 3D, write binary MSH.
//
//   g++ -O2 -o gmsh_extrude gmsh_extrude.cpp -lgmsh
//   ./gmsh_extrude plan.msh 41 -10050 peer.msh
#include <gmsh.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: gmsh_extrude PLAN.msh LAYERS DEPTH OUT.msh\n");
    return 2;
  }
  const std::string plan = argv[1], out = argv[4];
  const int layers = std::atoi(argv[2]);
  const double depth = std::atof(argv[3]);
  try {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::merge(plan);
    gmsh::model::mesh::createTopology();
    gmsh::vectorpair surfaces, extruded;
    gmsh::model::getEntities(surfaces, 2);
    gmsh::model::geo::extrude(surfaces, 0, 0, depth, extruded, {layers}, {}, false);
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::generate(3);
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, 3);
    std::size_t tets = 0;
    for (std::size_t k = 0; k < types.size(); ++k)
      if (types[k] == 4) tets += tags[k].size();
    std::vector<std::size_t> ntags;
    std::vector<double> xyz, par;
    gmsh::model::mesh::getNodes(ntags, xyz, par);
    gmsh::option::setNumber("Mesh.Binary", 1);
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::write(out);
    std::printf("gmsh_extrude: %zu nodes, %zu tetrahedra\n", ntags.size(), tets);
    gmsh::finalize();
  } catch (const std::string& e) {
    std::fprintf(stderr, "gmsh_extrude: error: %s\n", e.c_str());
    return 1;
  }
  return 0;
}
