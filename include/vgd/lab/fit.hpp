#pragma once
// Fabric fingerprints (seed 002): a cloth model's parameters fitted by
// least squares to a fabric's measurements, written as an XVC MATERIAL
// (docs/fabric-lab.md, "vgd lab fit").
//
// The measurements are a CSV file, one a line:
//
//   quantity,direction,x,value,unit
//   weight,,,200,g/m2
//   tensile,warp,0.01,50,N/m
//
// quantity is one of weight, thickness, tensile (a point of a stress-strain
// curve: x the engineering strain, value the stress per width), tensile_modulus,
// bending_rigidity (KES-FB2, the plate's B_θ), bending_length (FAST-2 / ASTM
// D1388 cantilever, Peirce's c) and shear_rigidity (KES-FB1, Q̄₆₆ at the
// angle); direction is warp, weft, bias or an angle from the warp in degrees.
// Each measurement is predicted by the lab's own forward formulas (the lab's
// references), and the parameters minimise the sum of squared relative
// residuals (Eigen's Levenberg–Marquardt on the logarithms of the positive ones).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/scene/material.hpp"
#include "vgd/scene/scene.hpp"

namespace vgd::lab {

enum class Measure { weight, thickness, tensile, tensile_modulus, bending_rigidity, bending_length, shear_rigidity };
const char* to_string(Measure m);

struct Measurement {
  Measure kind = Measure::weight;
  double angle_deg = 0.0;  // from the warp
  double x = 0.0;          // tensile: engineering strain (–); else unused
  double value = 0.0;      // SI: kg/m², m, N/m, N·m
  int line = 0;            // in the CSV, for messages
};

// Reads the CSV. Throws vgd::Error naming the file, the line and the problem,
// also for more than max_rows measurements (the fit's cost grows with them).
inline constexpr std::size_t kMaxMeasurements = 10000;
std::vector<Measurement> read_measurements(const std::filesystem::path& file,
                                           std::size_t max_rows = kMaxMeasurements);
// The same from the CSV's text; `name` is the file in messages.
std::vector<Measurement> parse_measurements(std::string_view text, const std::string& name,
                                            std::size_t max_rows = kMaxMeasurements);

// The value the material predicts for a measurement with the model's forward
// formula; NaN where the model has none (mass-spring off the yarns).
double predict(const Measurement& m, const scene::MaterialDef& material, scene::ClothModel model);

struct FitResidual {
  Measurement measurement;
  double fitted = 0.0;        // SI, the fitted material's prediction
  double rel_residual = 0.0;  // fitted / measured − 1 (NaN: not used)
};

struct FitResult {
  scene::MaterialDef material;                  // name = the given id
  scene::ClothModel model = scene::ClothModel::strain_rosette;
  std::vector<FitResidual> residuals;    // one per measurement, in file order
  std::vector<std::string> fitted;       // parameter names fitted
  std::vector<std::string> notes;        // parameters held, measurements not used
  double rms_rel_residual = 0.0;         // over the measurements used
  int iterations = 0;
};

// Fits the model's parameters. Throws vgd::Error(file, ...) when the
// measurements cannot determine a parameter the model needs (naming what to add).
FitResult fit(const std::vector<Measurement>& measurements, scene::ClothModel model, const std::string& id,
              const std::string& file);

// One residual in words: "LINE QUANTITY [ANGLE deg] [strain X]: measured M, fitted F, ±R" (SI).
std::string describe(const FitResidual& r);

// The fitted MATERIAL as an XVC document (id `id`) with a header comment that
// names the source and lists the residuals; written atomically.
std::string material_xvc(const FitResult& fit, const std::string& id, const std::string& source);
void write_material_xvc(const FitResult& fit, const std::filesystem::path& file, const std::string& source);

}  // namespace vgd::lab
