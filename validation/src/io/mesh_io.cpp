// Tileable meshes on disk (mesh_io.hpp): PLY (binary little-endian) and OBJ of a surface on the
// periodic Delaunay triangulation of a rank-1 lattice.
#include "swell/validation/io/mesh_io.hpp"

#include <fmt/format.h>

#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>
#include <unordered_map>

#include "swell/reference/errors.hpp"

namespace swell::validation {
namespace {

namespace fs = std::filesystem;
using reference::LatticeMesh;

// A file written through a buffer with C stdio, whose errors carry errno: a failure names the
// path and the system's reason. A file not committed (an exception on the way) is removed, so
// no half-written mesh is left behind.
class OutputFile {
 public:
  explicit OutputFile(const fs::path& path) : path_(path) {
    errno = 0;
    file_ = std::fopen(path.c_str(), "wb");
    if (file_ == nullptr) fail("cannot open for writing");
    // Only a regular file is removed on failure, never what else the path may name (a device).
    std::error_code ignored;
    removable_ = fs::is_regular_file(path_, ignored);
    buffer_.reserve(kChunk + 256);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() {
    if (file_ != nullptr) {
      std::fclose(file_);
      remove();
    }
  }

  std::string& buffer() { return buffer_; }
  // Call after each record: writes the buffer out once it holds a chunk.
  void maybe_flush() {
    if (buffer_.size() >= kChunk) flush();
  }
  void commit() {
    flush();
    errno = 0;
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) {
      const int error = errno;
      remove();
      errno = error;
      fail("write failed");
    }
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;

  void flush() {
    errno = 0;
    if (!buffer_.empty() &&
        std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) {
      fail("write failed");
    }
    buffer_.clear();
  }
  void remove() const {
    std::error_code ignored;
    if (removable_) fs::remove(path_, ignored);
  }
  [[noreturn]] void fail(const char* what) const {
    const int error = errno;
    throw InvalidInput(fmt::format("{}: {}: {}", path_.string(), what,
                                   error != 0 ? std::strerror(error) : "unknown error"));
  }

  fs::path path_;
  std::FILE* file_ = nullptr;
  bool removable_ = false;
  std::string buffer_;
};

void check_field(const std::vector<double>& values, const char* name, std::int64_t points,
                 bool may_be_empty) {
  if (may_be_empty && values.empty()) return;
  if (static_cast<std::int64_t>(values.size()) != points) {
    throw InvalidInput(fmt::format(
        "surface {}: number of values must be {}, one per lattice point{} (got {})", name,
        points, may_be_empty ? ", or none" : "", values.size()));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidInput(fmt::format("surface {}[{}] must be finite (got {})", name, i, values[i]));
    }
  }
}

void check_surface(const MeshSurface& surface) {
  const LatticeMesh& mesh = surface.mesh;
  const std::int64_t n = mesh.points;
  // The lattice the positions come from, as periodic_delaunay leaves it (a mesh built by hand
  // could break it; the triangles are checked by TileNumbering).
  if (n < 3 || mesh.g0 < 0 || mesh.g0 >= n || mesh.g1 < 0 || mesh.g1 >= n ||
      !(std::isfinite(mesh.lx) && mesh.lx > 0 && std::isfinite(mesh.ly) && mesh.ly > 0)) {
    throw InvalidInput(
        fmt::format("mesh: must have points ≥ 3, a generator in [0, points) and "
                    "finite positive lengths, as periodic_delaunay makes it (got "
                    "points = {}, g = ({}, {}), {} x {} m)",
                    n, mesh.g0, mesh.g1, mesh.lx, mesh.ly));
  }
  check_field(surface.h, "h", n, false);
  check_field(surface.dx, "dx", n, true);
  check_field(surface.dy, "dy", n, true);
}

// The displaced, shifted position of a vertex, rounded to the float both files hold.
std::array<float, 3> vertex_position(const MeshSurface& s, const TileVertex& v) {
  const auto [x, y] = s.mesh.position(v.point);
  const auto i = static_cast<std::size_t>(v.point);
  const double dx = s.dx.empty() ? 0.0 : s.dx[i];
  const double dy = s.dy.empty() ? 0.0 : s.dy[i];
  return {static_cast<float>(x + v.px * s.mesh.lx + dx),
          static_cast<float>(y + v.py * s.mesh.ly + dy), static_cast<float>(s.h[i])};
}

std::string describe(const LatticeMesh& mesh) {
  return fmt::format(
      "periodic Delaunay mesh of the rank-1 lattice N = {}, g = ({}, {}) on a {} x {} m patch",
      mesh.points, mesh.g0, mesh.g1, mesh.lx, mesh.ly);
}

void put_u32(std::string& out, std::uint32_t value) {
  for (int byte = 0; byte < 4; ++byte)
    out.push_back(static_cast<char>((value >> (8 * byte)) & 0xffu));
}

void put_float_text(std::string& out, float value) {
  char text[32];
  // Shortest decimal that reads back to this float: the OBJ and the PLY hold the same numbers.
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

void put_int_text(std::string& out, std::int64_t value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

// The tileable mesh's numbering without materializing it: vertex n < N is point n unshifted, and
// only the shifted duplicates — the corners of the triangles along two sides of the patch,
// O(√N) of them — are listed and looked up. So a writer needs O(√N) memory beside the mesh.
class TileNumbering {
 public:
  explicit TileNumbering(const LatticeMesh& mesh) : mesh_(mesh) {
    const std::int64_t n = mesh.points;
    if (n < 3 || mesh.triangles.size() != static_cast<std::size_t>(2 * n) ||
        mesh.corner_periods.size() != mesh.triangles.size()) {
      throw InvalidInput(fmt::format(
          "mesh: must have 2·points triangles and corner periods, with points ≥ 3 (got "
          "points = {}, {} triangles, {} corner periods)",
          n, mesh.triangles.size(), mesh.corner_periods.size()));
    }
    constexpr auto kMaxVertices =
        static_cast<std::int64_t>(std::numeric_limits<std::int32_t>::max());
    if (n > kMaxVertices) {
      throw InvalidInput(fmt::format(
          "mesh: points must be at most 2^31 − 1 for a mesh file's 32-bit vertex indices (got {})",
          n));
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const std::int64_t point = mesh.triangles[t][k];
        const auto [px, py] = mesh.corner_periods[t][k];
        if (point < 0 || point >= n || px < -1 || px > 1 || py < -1 || py > 1) {
          throw InvalidInput(fmt::format(
              "mesh: triangle {} corner {} must name a point in [0, {}) with periods in "
              "{{-1, 0, 1}} (got point {}, periods ({}, {}))",
              t, k, n, point, px, py));
        }
        if (px == 0 && py == 0) continue;
        const std::int64_t next = vertex_count();
        const auto [it, added] = index_.try_emplace(key(point, px, py), 0);
        if (!added) continue;
        if (next > kMaxVertices) {
          throw InvalidInput(fmt::format(
              "mesh: a mesh file holds at most 2^31 vertices; this one needs more ({} points "
              "and their duplicates)",
              n));
        }
        it->second = static_cast<std::int32_t>(next);
        duplicates_.push_back({point, px, py});
      }
    }
  }

  std::int64_t vertex_count() const {
    return mesh_.points + static_cast<std::int64_t>(duplicates_.size());
  }
  // The vertices after the N lattice points, in order.
  const std::vector<TileVertex>& duplicates() const { return duplicates_; }
  std::array<std::int32_t, 3> face(std::size_t t) const {
    std::array<std::int32_t, 3> face{};
    for (int k = 0; k < 3; ++k) {
      const std::int64_t point = mesh_.triangles[t][k];
      const auto [px, py] = mesh_.corner_periods[t][k];
      face[k] =
          px == 0 && py == 0 ? static_cast<std::int32_t>(point) : index_.at(key(point, px, py));
    }
    return face;
  }

 private:
  static std::int64_t key(std::int64_t point, int px, int py) {
    return point * 9 + (px + 1) * 3 + (py + 1);
  }

  const LatticeMesh& mesh_;
  std::vector<TileVertex> duplicates_;
  std::unordered_map<std::int64_t, std::int32_t> index_;
};

}  // namespace

TileableMesh tileable_mesh(const LatticeMesh& mesh) {
  const TileNumbering numbering(mesh);
  TileableMesh out;
  out.vertices.reserve(static_cast<std::size_t>(numbering.vertex_count()));
  for (std::int64_t n = 0; n < mesh.points; ++n) out.vertices.push_back({n, 0, 0});
  out.vertices.insert(out.vertices.end(), numbering.duplicates().begin(),
                      numbering.duplicates().end());
  out.faces.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) out.faces.push_back(numbering.face(t));
  return out;
}

void write_ply(const fs::path& path, const MeshSurface& surface) {
  check_surface(surface);
  const TileNumbering numbering(surface.mesh);
  OutputFile file(path);
  std::string& out = file.buffer();
  out += "ply\nformat binary_little_endian 1.0\n";
  out += fmt::format("comment swell: {}\n", describe(surface.mesh));
  out += fmt::format("comment tileable: copies at offsets (i*{}, j*{}) form a seamless surface\n",
                     surface.mesh.lx, surface.mesh.ly);
  out += fmt::format("element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
                     numbering.vertex_count());
  out += fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                     surface.mesh.triangles.size());
  // Bytes assembled explicitly, so the file is little-endian whatever the machine.
  const auto put_vertex = [&](const TileVertex& v) {
    for (const float value : vertex_position(surface, v)) {
      put_u32(out, std::bit_cast<std::uint32_t>(value));
    }
    file.maybe_flush();
  };
  for (std::int64_t n = 0; n < surface.mesh.points; ++n) put_vertex({n, 0, 0});
  for (const TileVertex& v : numbering.duplicates()) put_vertex(v);
  for (std::size_t t = 0; t < surface.mesh.triangles.size(); ++t) {
    out.push_back(3);
    for (const std::int32_t index : numbering.face(t))
      put_u32(out, static_cast<std::uint32_t>(index));
    file.maybe_flush();
  }
  file.commit();
}

void write_obj(const fs::path& path, const MeshSurface& surface) {
  check_surface(surface);
  const TileNumbering numbering(surface.mesh);
  OutputFile file(path);
  std::string& out = file.buffer();
  out += fmt::format("# swell: {}\n", describe(surface.mesh));
  out += fmt::format("# tileable: copies at offsets (i*{}, j*{}) form a seamless surface\n",
                     surface.mesh.lx, surface.mesh.ly);
  out += fmt::format("# {} vertices ({} lattice points, then shifted duplicates), {} faces\n",
                     numbering.vertex_count(), surface.mesh.points, surface.mesh.triangles.size());
  const auto put_vertex = [&](const TileVertex& v) {
    out += 'v';
    for (const float value : vertex_position(surface, v)) {
      out += ' ';
      put_float_text(out, value);
    }
    out += '\n';
    file.maybe_flush();
  };
  for (std::int64_t n = 0; n < surface.mesh.points; ++n) put_vertex({n, 0, 0});
  for (const TileVertex& v : numbering.duplicates()) put_vertex(v);
  for (std::size_t t = 0; t < surface.mesh.triangles.size(); ++t) {
    out += 'f';
    for (const std::int32_t index : numbering.face(t)) {
      out += ' ';
      put_int_text(out, std::int64_t{index} + 1);
    }
    out += '\n';
    file.maybe_flush();
  }
  file.commit();
}

}  // namespace swell::validation
