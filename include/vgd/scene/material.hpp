#pragma once
// Cloth materials of a scene: the fabric values a cloth model needs, given
// inline in the scene file or read from an XVC document's MATERIAL module.
//
// One vocabulary of parameter names serves both (docs/scene.md, "Materials"):
// a scene file's inline material and an XVC MATERIAL's PARAMETER children use
// the same names and units, e.g.
//
//   <MATERIAL id="flag-cloth" name="seed 000 flag">
//     <PARAMETER id="param1" name="particle_mass" value="0.1" unit="kg"/>
//     <PARAMETER id="param2" name="spring.warp" value="1800" unit="N/m"/>
//   </MATERIAL>
//
// Values are converted to SI; a unit of the wrong kind, an unknown parameter
// name, a value out of range or a missing module is refused with a vgd::Error
// naming the file, the module and the parameter.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "vgd/scene/units.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/material.hpp"

namespace vgd::xvc {
class Document;
}

namespace vgd::scene {

// The values of one fabric, SI. A model uses its own part: mass_spring for
// the mass-spring model, orthotropic for the strain rosette and bending; the
// mass comes from particle_mass (mass-spring only) or density.
struct MaterialDef {
  std::string name;            // for messages and reports
  double density = 0.0;        // kg/m², areal density (masses = triangle area × density / 3); 0 = not given
  double particle_mass = 0.0;  // kg per particle, mass-spring only (seed 000's particle_mass); 0 = not given
  double thickness = 0.0;      // m; needed only to convert values given per volume (Pa, kg/m³); 0 = not given
  // Largest warp and weft strain the yarns allow (sim/effects/strain_limit.hpp),
  // either cloth model; dimensionless, 0 = none.
  double strain_limit = 0.0;
  std::optional<sim::MassSpringMaterial> mass_spring;  // set when any spring.* parameter is given
  // Set when any membrane or bending parameter (E_warp, G, B_warp, ...) is
  // given; its density and thickness are the ones above.
  std::optional<sim::OrthotropicMaterial> orthotropic;
};

// One entry of a scene's material table: values here, or a MATERIAL module of
// an XVC document.
struct MaterialSource {
  std::filesystem::path xvc;  // XVC document; empty: `values` are the material
  std::string id;             // the MATERIAL's id in that document
  MaterialDef values;
};

// A parameter name the material vocabulary knows.
struct MaterialParameter {
  std::string_view name;      // e.g. "spring.warp"
  Dimension dimension;        // the SI dimension of its value
  std::string_view unit;      // SI unit as XVC writes it, e.g. "N/m"
  std::string_view meaning;   // one sentence, with a typical value
};
std::span<const MaterialParameter> material_parameters();
const MaterialParameter* find_material_parameter(std::string_view name);

// Sets a parameter on `m` from a value in SI units of `unit_dimension`.
// Pressures (Pa) for membrane moduli and volume densities (kg/m³) are
// multiplied by the material's thickness, which must then already be set.
// Throws vgd::Error(file, entity, ...) for an unknown name, a unit of the
// wrong kind, a missing thickness or a value out of range.
void set_material_parameter(MaterialDef& m, std::string_view name, double value, const Dimension& unit_dimension,
                            const std::string& file, const std::string& entity);

// The MATERIAL with this id in the document, converted. `file` names the
// document in messages. Throws vgd::Error when there is no such MATERIAL or a
// PARAMETER is unknown or invalid.
MaterialDef material_from_xvc(const xvc::Document& doc, std::string_view id, const std::string& file);

// Loads the document and converts its MATERIAL `id`.
MaterialDef load_xvc_material(const std::filesystem::path& file, std::string_view id);

// Why a material cannot serve a model, in one sentence ("" when it can): no
// values for that model, no mass, or (strain rosette) what
// sim::problems(OrthotropicMaterial) finds.
std::string mass_spring_problem(const MaterialDef& m);
std::string orthotropic_problem(const MaterialDef& m);

// The orthotropic material with the MaterialDef's density and thickness.
sim::OrthotropicMaterial orthotropic_of(const MaterialDef& m);

// `layers` plies of the fabric lying on one another, not bonded (a rib cut
// double and folded): the areal density, particle mass, thickness, every
// stiffness (sheet moduli, springs, bending rigidities, twist) and the
// springs' damping times `layers`; Poisson's ratios, residual strains and
// the strain limit as they are, and curves' stresses times `layers`. The
// name says how many plies.
MaterialDef layered(const MaterialDef& m, int layers);

// The fabric a piece of a garment document is cut from: the MATERIAL its
// PATTERN names as its own (xvc::piece_material; the pattern found by block
// or piece name, any size; `file` names the document in errors), else
// `garment_fabric`.
MaterialDef piece_fabric(const xvc::Document& garment, std::string_view piece, const MaterialDef& garment_fabric,
                         const std::string& file);

}  // namespace vgd::scene
