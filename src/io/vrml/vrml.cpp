// The static and animated VRML97 flavours (vrml.hpp): the garment's pieces as
// IndexedFaceSets sharing one Coordinate, one TextureCoordinate (the
// material coordinates) and, when static, one Normal; the body as a Shape.
#include "vgd/io/vrml/vrml.hpp"

#include <algorithm>
#include <cmath>

#include <zlib.h>

#include "text.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::io::vrml {

namespace {

using detail::append_faces;
using detail::append_points;
using detail::append_uv;
using detail::def_name;

// The pieces as `DEF GarmentPieces Group { children [ Shape ... ] }`. The first
// non-empty piece defines the shared GarmentCoord, GarmentTexCoord and (with
// normals) GarmentNormal nodes; the others USE them.
std::string piece_shapes(const Garment& g, const OutputMesh& mesh, const std::vector<float>& x, int decimals,
                         bool normals, double crease) {
  std::string o = "DEF GarmentPieces Group { children [\n";
  bool defined = false;
  std::vector<std::array<double, 3>> nrm;
  if (normals) nrm = vertex_normals(mesh, x);
  for (int p = 0; p < static_cast<int>(mesh.pieces.size()); ++p) {
    const auto& faces = mesh.pieces[p];
    if (faces.coord.empty()) continue;
    const std::string name = g.cloth.pieces.empty() ? "cloth" : g.cloth.pieces[p];
    o += "  DEF " + def_name("Piece_", name) + " Shape {\n";
    o += "    appearance " + detail::appearance(g.look(p), 4) + "\n";
    o += "    geometry IndexedFaceSet {\n";
    if (!defined) {
      o += "      coord DEF GarmentCoord Coordinate { point ";
      append_points(o, x, mesh.vertex_particle, decimals, 8);
      o += " }\n";
      if (normals) {
        o += "      normal DEF GarmentNormal Normal { vector [\n";
        for (std::size_t v = 0; v < nrm.size(); ++v) {
          o += v % 6 == 0 ? "        " : "";
          append_number(o, nrm[v][0], 3), o += ' ', append_number(o, nrm[v][1], 3), o += ' ';
          append_number(o, nrm[v][2], 3);
          o += (v % 6 == 5 || v + 1 == nrm.size()) ? ",\n" : ", ";
        }
        o += "      ] }\n";
      }
      o += "      texCoord DEF GarmentTexCoord TextureCoordinate { point ";
      append_uv(o, g.cloth.uv, decimals, 8);
      o += " }\n";
      defined = true;
    } else {
      o += "      coord USE GarmentCoord\n";
      if (normals) o += "      normal USE GarmentNormal\n";
      o += "      texCoord USE GarmentTexCoord\n";
    }
    o += "      coordIndex ";
    append_faces(o, faces.coord, 8);
    o += "\n      texCoordIndex ";
    append_faces(o, faces.tex, 8);
    o += "\n      solid FALSE\n      ccw TRUE\n      creaseAngle ";
    append_number(o, crease, 3);
    o += "\n    }\n  }\n";
  }
  return o + "] }\n";
}

int resolve_frame(const Garment& g, int frame) {
  const int n = g.frames.count();
  if (frame < 0) frame = n - 1;
  if (frame >= n) throw Error(g.name, "", "frame " + std::to_string(frame) + " does not exist (" + std::to_string(n) +
                                              " frames)");
  return frame;
}

std::string summary(const Garment& g, const OutputMesh& mesh, double crease, double h) {
  return std::to_string(mesh.vertex_particle.size()) + " vertices, " + std::to_string(mesh.face_count()) +
         " triangles in " + std::to_string(g.cloth.num_pieces()) + " pieces; creaseAngle " +
         format_fixed(crease, 2) + " rad from the median edge " +
         std::to_string(static_cast<int>(std::lround(h * 1000))) + " mm (docs/vrml.md)";
}

}  // namespace

std::string static_vrml(const Garment& g, const StaticOptions& options) {
  g.validate();
  const int decimals = detail::checked_decimals(options.precision);
  const int frame = resolve_frame(g, options.frame);
  const auto& x = g.frames.positions[frame];
  const OutputMesh mesh = output_mesh(g.cloth, true);
  const double h = median_edge_length(g.cloth);
  const double crease = options.crease_angle >= 0 ? options.crease_angle : crease_angle(h);

  std::string o = detail::preamble(
      g.name, {"vgd static drape of '" + g.name + "': frame " + std::to_string(frame) + " at t = " +
                   std::to_string(g.frames.times[frame]) + " s",
               summary(g, mesh, crease, h)},
      detail::garment_box(g, frame));
  o += piece_shapes(g, mesh, x, decimals, options.normals, crease);
  if (options.body && g.body) o += detail::body_shape(*g.body, options.body_precision);
  return o;
}

std::string animated_vrml(const Garment& g, const AnimatedOptions& options) {
  g.validate();
  VGD_ASSERT(options.decimate >= 1, "decimate must be at least 1");
  VGD_ASSERT(options.speed > 0, "speed must be positive");
  const int decimals = detail::checked_decimals(options.precision);
  // Frames kept: every Nth and the last.
  std::vector<int> kept;
  const int n = g.frames.count();
  for (int f = 0; f < n; f += options.decimate) kept.push_back(f);
  if (kept.back() != n - 1) kept.push_back(n - 1);
  // One vertex per particle: seams close during the run.
  const OutputMesh mesh = output_mesh(g.cloth, false);
  const double h = median_edge_length(g.cloth);
  const double crease = options.crease_angle >= 0 ? options.crease_angle : crease_angle(h);
  const double t0 = g.frames.times[kept.front()], t1 = g.frames.times[kept.back()];
  const double duration = std::max(t1 - t0, 1e-3);

  std::string o = detail::preamble(
      g.name, {"vgd animated drape of '" + g.name + "': " + std::to_string(kept.size()) + " of " +
                   std::to_string(n) + " frames (every " + std::to_string(options.decimate) + "), " +
                   std::to_string(t1 - t0) + " s",
               summary(g, mesh, crease, h)},
      detail::garment_box(g, kept.back()));
  // Normals are left to the viewer (creaseAngle): they change every frame.
  o += piece_shapes(g, mesh, g.frames.positions[kept.front()], decimals, false, crease);
  if (options.body && g.body) o += detail::body_shape(*g.body, options.body_precision);

  // The clock and the interpolator: key = fraction of the run, keyValue = every kept frame.
  o += "DEF Clock TimeSensor { cycleInterval ";
  append_number(o, duration / options.speed, 4);
  o += options.loop ? " loop TRUE }\n" : " loop FALSE }\n";
  o += "DEF Motion CoordinateInterpolator {\n  key [";
  for (std::size_t k = 0; k < kept.size(); ++k) {
    o += k % 12 == 0 ? "\n    " : " ";
    append_number(o, (g.frames.times[kept[k]] - t0) / duration, 5);
  }
  o += "\n  ]\n  keyValue [\n";
  for (int f : kept) {
    o += "    # frame " + std::to_string(f) + "\n";
    detail::append_point_lines(o, g.frames.positions[f], mesh.vertex_particle, decimals, 4);
  }
  o += "  ]\n}\n";
  o += "ROUTE Clock.fraction_changed TO Motion.set_fraction\n";
  o += "ROUTE Motion.value_changed TO GarmentCoord.set_point\n";
  return o;
}

std::string gzip(std::string_view text) {
  z_stream z{};
  // windowBits 15 + 16: a gzip header and trailer (RFC 1952), as VRML97 §4.1 allows for .wrl files.
  VGD_ASSERT(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) == Z_OK, "zlib deflateInit2 failed");
  std::string out(deflateBound(&z, static_cast<uLong>(text.size())) + 32, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  VGD_ASSERT(rc == Z_STREAM_END, "zlib deflate did not finish");
  return out;
}

void write_vrml(const std::filesystem::path& path, std::string_view text) {
  if (path.extension() == ".gz" || path.extension() == ".wrz") write_file_atomic(path, gzip(text));
  else write_file_atomic(path, text);
}

}  // namespace vgd::io::vrml
