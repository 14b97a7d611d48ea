#pragma once
// Tileable meshes on disk (PLY, OBJ) of a surface sampled on a rank-1 lattice, triangulated by
// reference::periodic_delaunay.
//
// Tileable: copies of the file's mesh placed side by side at offsets (i·lx, j·ly) form one
// seamless surface. The file holds exactly one copy of each of the 2N triangles; a triangle
// that crosses the patch's edge keeps its corners next to each other by using duplicated
// vertices at the shifted positions x_n + (px·lx, py·ly). Vertices, in this order:
//   - vertex n (n = 0 … N−1) is lattice point n unshifted, at (x_n + dx_n, y_n + dy_n, h_n);
//   - then each (point n, period (px, py) ≠ (0, 0)) some triangle corner uses, once, in the
//     order of first use over the triangles, at (x_n + dx_n + px·lx, y_n + dy_n + py·ly, h_n).
// A duplicate is the vertex that a neighbouring copy's vertex n lands on, so the copies share
// their seam vertices (to float rounding) and every seam edge meets its twin. There are about
// O(√N) duplicates (the triangles along two sides of the patch).
//
//   PLY: binary little-endian; element vertex with float x, y, z; element face with
//        list uchar int vertex_indices (0-based, counter-clockwise seen from +z).
//   OBJ: text; "v x y z" and "f i j k" lines (1-based, counter-clockwise), values as the
//        shortest decimal that reads back to the float the PLY holds.
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "swell/reference/lattice_mesh.hpp"

namespace swell::validation {

// A surface on the mesh: per lattice point n the displaced position (x_n + dx_n, y_n + dy_n, h_n),
// metres. The points x_n themselves come from the mesh (its lattice, generator and patch), so
// the positions cannot disagree with the triangles. dx, dy may be empty (no horizontal
// displacement); otherwise h, dx, dy hold mesh.points finite values each. A plain aggregate:
// move the mesh in (it is 60 bytes per point).
struct MeshSurface {
  reference::LatticeMesh mesh;
  std::vector<double> h, dx, dy;
};

// One vertex of the tileable mesh: lattice point `point` shifted by (px·lx, py·ly).
struct TileVertex {
  std::int64_t point = 0;
  std::int8_t px = 0, py = 0;
};

// The vertices and faces the files hold (the order described above). Faces index vertices,
// counter-clockwise, one per triangle of the mesh, in its order. Throws InvalidInput when the
// mesh is inconsistent (sizes, a point index or period out of range) or would need more than
// 2^31 vertices (PLY's int index). The writers number vertices the same way without building
// this (they keep only the O(√N) duplicates).
struct TileableMesh {
  std::vector<TileVertex> vertices;
  std::vector<std::array<std::int32_t, 3>> faces;
};
TileableMesh tileable_mesh(const reference::LatticeMesh& mesh);

// Write the surface as a tileable mesh. Throw InvalidInput for a surface that breaks the rules
// above (naming the field, the rule and the value) and for a file that cannot be opened or
// written (naming the path and the system's reason); a partly written file is removed.
void write_ply(const std::filesystem::path& path, const MeshSurface& surface);
void write_obj(const std::filesystem::path& path, const MeshSurface& surface);

}  // namespace swell::validation
