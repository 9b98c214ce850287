// Bodies as designers bring them: generated from vgd's mannequin (A-pose and
// T-pose), written in other units, up axes and facings, with helper meshes and
// loose parts, as a skinned glTF under a scaled and rotated armature; each must
// come in upright, facing +Z, at its true height, vertex for vertex. And the
// files that are no body at all get an error that says what is wrong.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "support/errors.hpp"
#include "support/test_paths.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/body/landmarks.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/body/model_file.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/units.hpp"

namespace vgd::body {
namespace {

// The size-38 mannequin in a pose: 'A' (arms at 45°), 'T' (90°) or 'F'
// (45°, swung 30° forward).
const Avatar& mannequin(char pose) {
  auto make = [](double angle, double forward) {
    MannequinOptions o;
    o.target_triangles = 5000;
    o.arm_angle_deg = angle;
    o.arm_forward_deg = forward;
    return make_mannequin(BodyMeasurements{}, o);
  };
  static const Avatar a = make(45.0, 0.0);
  static const Avatar t = make(90.0, 0.0);  // arms straight out: the arm span is longer than the body is tall
  static const Avatar f = make(45.0, 30.0);
  return pose == 'T' ? t : pose == 'F' ? f : a;
}

// The body recentred as the importer recentres (feet on y = 0, box centred on x = z = 0).
mesh::SurfaceMesh recentred(mesh::SurfaceMesh s) {
  const mesh::Box3 b = mesh::bounding_box(s);
  mesh::translate(s, Vec3(-b.centre().x(), -b.min.y(), -b.centre().z()));
  return s;
}

// Rotation taking vgd's frame (+Y up, facing +Z) to a file whose up is `up` and
// whose body faces `facing` (given in the file's frame once up is turned to +Y).
Eigen::Matrix3d to_file(const std::string& up, const std::string& facing) {
  Eigen::Matrix3d face;  // +Z -> facing, about +Y
  if (facing == "+z") face.setIdentity();
  else if (facing == "-z") face << -1, 0, 0, 0, 1, 0, 0, 0, -1;
  else if (facing == "+x") face << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  else face << 0, 0, -1, 0, 1, 0, 1, 0, 0;
  Eigen::Matrix3d tilt;  // +Y -> up
  if (up == "y") tilt.setIdentity();
  else if (up == "-y") tilt << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  else if (up == "z") tilt << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  else if (up == "-z") tilt << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  else if (up == "x") tilt << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  else tilt << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // -x
  return tilt * face;
}

// OBJ text of `s` moved by (scale · rotation, shift), as group `name`;
// `first` is the 1-based index of its first vertex in the file.
std::string obj_group(const mesh::SurfaceMesh& s, const std::string& name, double scale, const Eigen::Matrix3d& rot,
                      const Vec3& shift, int first) {
  std::ostringstream out;
  out.precision(9);
  out << "g " << name << "\n";
  for (const auto& v : s.vertices) {
    const Vec3 p = scale * (rot * v) + shift;
    out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
  }
  for (const auto& t : s.triangles) out << "f " << t[0] + first << ' ' << t[1] + first << ' ' << t[2] + first << "\n";
  return out.str();
}

// Largest distance (m) from a vertex of either mesh to the nearest vertex of
// the other, both recentred (assimp may reorder vertices between groups).
double vertex_error(const Avatar& got, const mesh::SurfaceMesh& want) {
  const mesh::SurfaceMesh w = recentred(want);
  if (got.surface.num_vertices() != w.num_vertices()) return 1e9;
  auto one_way = [](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
    double worst = 0;
    for (const auto& p : from) {
      double best = 1e300;
      for (const auto& q : to) best = std::min(best, (p - q).squaredNorm());
      worst = std::max(worst, best);
    }
    return std::sqrt(worst);
  };
  return std::max(one_way(got.surface.vertices, w.vertices), one_way(w.vertices, got.surface.vertices));
}

struct PoseCase {
  char pose;  // 'A', 'T' or 'F' (arms forward)
  std::string unit, up, facing;
  std::string format = "obj";  // obj: written by the test; others: through export_avatar (assimp)
};

void PrintTo(const PoseCase& c, std::ostream* os) {
  *os << c.format << ' ' << c.pose << "-pose " << c.unit << " up " << c.up << " facing " << c.facing;
}

class ImportedBody : public ::testing::TestWithParam<PoseCase> {};

TEST_P(ImportedBody, ComesInUprightFacingForwardAtItsHeight) {
  const PoseCase& c = GetParam();
  const Avatar& body = mannequin(c.pose);
  if (c.pose == 'T') {
    // The case that fooled the longest-extent rule: arm span over height.
    const Vec3 size = mesh::bounding_box(body.surface).size();
    ASSERT_GT(size.x(), size.y()) << "not a T-pose";
  }
  const double scale = 1.0 / metres_per(*parse_length_unit(c.unit));
  // One directory per case: ctest runs the cases in parallel.
  const std::string stem = std::string(1, c.pose) + "-" + c.unit + "-" + c.up + "-" + c.facing.substr(1) +
                           (c.facing[0] == '-' ? "neg" : "pos");
  const auto dir = test::scratch_dir("avatar_pose/" + stem + "-" + c.format);
  auto file = dir / (stem + ".obj");
  if (c.format == "obj") {
    write_file_atomic(file, obj_group(body.surface, "body", scale, to_file(c.up, c.facing), Vec3(0.3, -0.2, 0.1) * scale, 1));
  } else {
    Avatar moved = body;
    mesh::transform(moved.surface, scale * to_file(c.up, c.facing), Vec3(0.3, -0.2, 0.1) * scale);
    file.replace_extension("." + c.format);
    export_avatar(moved, file);
  }
  AvatarReport r;
  const Avatar got = import_avatar(file, {}, &r);
  EXPECT_EQ(r.unit, c.unit) << r.unit_reason;
  EXPECT_EQ(r.up, c.up) << r.up_reason;
  EXPECT_EQ(r.facing, c.facing) << r.facing_reason;
  const double height = mesh::bounding_box(body.surface).size().y();
  EXPECT_NEAR(r.height, height, 0.01);
  EXPECT_LT(vertex_error(got, body.surface), 1e-4) << "not the mannequin vertex for vertex";
  // The importer says what it decided.
  ASSERT_GE(got.notes.size(), 3u);
  EXPECT_EQ(got.notes[0].rfind("unit " + c.unit, 0), 0u) << got.notes[0];
  // Measured and cut into all its segments, arms included.
  EXPECT_EQ(r.segments.size(), 7u) << ::testing::PrintToString(r.segments);
  for (const char* name : {"torso", "hips", "neck", "left-arm", "right-arm", "left-leg", "right-leg"})
    EXPECT_NE(got.segment(name), nullptr) << name;
}

INSTANTIATE_TEST_SUITE_P(
    Poses, ImportedBody,
    ::testing::Values(PoseCase{'A', "m", "y", "+z"}, PoseCase{'T', "m", "y", "+z"}, PoseCase{'T', "cm", "z", "+z"},
                      PoseCase{'T', "mm", "-z", "-x"}, PoseCase{'T', "dm", "y", "+x"}, PoseCase{'A', "in", "x", "-z"},
                      PoseCase{'T', "in", "-y", "-z"}, PoseCase{'A', "dm", "-x", "+x"},
                      PoseCase{'F', "m", "y", "+z"}, PoseCase{'F', "cm", "-y", "-x"}, PoseCase{'F', "in", "z", "+x"},
                      PoseCase{'A', "cm", "z", "+x", "dae"}, PoseCase{'T', "m", "-z", "+z", "fbx"},
                      PoseCase{'T', "mm", "y", "-x", "glb"}, PoseCase{'A', "in", "x", "+z", "ply"},
                      PoseCase{'F', "mm", "x", "-z", "glb"}),
    [](const auto& p) {
      const PoseCase& c = p.param;
      std::string up = c.up[0] == '-' ? "neg" + c.up.substr(1) : c.up;
      return c.format + "_" + std::string(1, c.pose) + "_" + c.unit + "_up_" + up + "_facing_" +
             (c.facing[0] == '-' ? "neg" : "pos") + c.facing.substr(1);
    });

// MakeHuman-style files: the body with helper meshes (clothes proxies,
// joints) and loose eyes, upside down. The body comes in alone, upright, and
// the notes say what was left out.
TEST(ImportedBodyWithHelpers, HelpersAndLoosePartsAreLeftOut) {
  const Avatar& body = mannequin('A');
  const auto dir = test::scratch_dir("avatar_helpers");
  const Eigen::Matrix3d rot = to_file("-y", "+z");
  // A helper as big as the legs (a tights proxy): a box round them.
  mesh::SurfaceMesh box;
  for (int i = 0; i < 8; ++i) box.vertices.emplace_back(i & 1 ? 0.2 : -0.2, i & 2 ? 0.8 : 0.0, i & 4 ? 0.15 : -0.15);
  for (const auto& t : std::vector<std::array<int, 3>>{{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}})
    box.triangles.push_back(t);
  mesh::SurfaceMesh eye = box;  // a small loose part inside the head
  for (auto& v : eye.vertices) v = Vec3(0.03, 1.6, 0.08) + 0.05 * v;
  std::string text = obj_group(body.surface, "body", 1.0, rot, Vec3::Zero(), 1);
  int next = body.surface.num_vertices() + 1;
  text += obj_group(box, "helper-tights", 1.0, rot, Vec3::Zero(), next);
  next += box.num_vertices();
  text += obj_group(box, "joint-l-knee", 1.0, rot, Vec3::Zero(), next);
  next += box.num_vertices();
  text += obj_group(eye, "l-eye", 1.0, rot, Vec3::Zero(), next);
  write_file_atomic(dir / "makehuman-like.obj", text);
  AvatarReport r;
  const Avatar got = import_avatar(dir / "makehuman-like.obj", {}, &r);
  EXPECT_EQ(r.up, "-y") << r.up_reason;
  EXPECT_EQ(r.meshes, 2) << "the body and the eye; helpers left out";
  EXPECT_LT(vertex_error(got, body.surface), 1e-4);
  std::string notes;
  for (const auto& n : r.notes) notes += n + "\n";
  EXPECT_NE(notes.find("helper-tights"), std::string::npos) << notes;
  EXPECT_NE(notes.find("loose part"), std::string::npos) << notes;
}

struct GltfJoint {
  std::string name;
  Vec3 p;  // m, in the mesh's bind pose
};

// `path` (.gltf, with its .bin beside it): `s` as one skinned mesh "Body" under
// a node "Armature" with the JSON transform members `armature`, skinned to
// `joints` (children of the armature at their positions; inverse bind
// matrices the translations to them), every vertex weighted to the first.
void write_skinned_gltf(const std::filesystem::path& path, const mesh::SurfaceMesh& s,
                        const std::vector<GltfJoint>& joints, const std::string& armature) {
  std::string bin;
  auto put = [&](const void* p, std::size_t n) { bin.append(static_cast<const char*>(p), n); };
  for (const auto& v : s.vertices) {
    const float f[3] = {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
    put(f, sizeof f);
  }
  const std::size_t joints_at = bin.size();
  for (int i = 0; i < s.num_vertices(); ++i) {
    const unsigned char j[4] = {0, 0, 0, 0};
    put(j, sizeof j);
  }
  const std::size_t weights_at = bin.size();
  for (int i = 0; i < s.num_vertices(); ++i) {
    const float w[4] = {1, 0, 0, 0};
    put(w, sizeof w);
  }
  const std::size_t index_at = bin.size();
  for (const auto& t : s.triangles) {
    const std::uint32_t q[3] = {static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                                static_cast<std::uint32_t>(t[2])};
    put(q, sizeof q);
  }
  const std::size_t ibm_at = bin.size();
  for (const auto& j : joints)
    for (int k = 0; k < 16; ++k) {
      float f = k % 5 == 0 ? 1.0f : 0.0f;
      if (k >= 12 && k < 15) f = static_cast<float>(-j.p[k - 12]);  // column-major: the translation
      put(&f, sizeof f);
    }
  const std::string bin_name = path.stem().string() + ".bin";
  write_file_atomic(path.parent_path() / bin_name, bin);
  std::string nodes = R"({"name": "Armature", "children": [1)";
  for (std::size_t k = 0; k < joints.size(); ++k) nodes += ", " + std::to_string(k + 2);
  nodes += "], " + armature + R"(}, {"name": "Body", "mesh": 0, "skin": 0})";
  std::string skin = "[";
  for (std::size_t k = 0; k < joints.size(); ++k) {
    char t[200];
    std::snprintf(t, sizeof t, R"(, {"name": "%s", "translation": [%g, %g, %g]})", joints[k].name.c_str(), joints[k].p.x(),
                  joints[k].p.y(), joints[k].p.z());
    nodes += t;
    skin += (k ? ", " : "") + std::to_string(k + 2);
  }
  skin += "]";
  const mesh::Box3 b = mesh::bounding_box(s);
  char gltf[8192];
  std::snprintf(gltf, sizeof gltf, R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [%s],
  "skins": [{"joints": %s, "inverseBindMatrices": 4}],
  "meshes": [{"name": "Body", "primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}, "indices": 3}]}],
  "buffers": [{"uri": "%s", "byteLength": %zu}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": %zu},
    {"buffer": 0, "byteOffset": %zu, "byteLength": %zu},
    {"buffer": 0, "byteOffset": %zu, "byteLength": %zu},
    {"buffer": 0, "byteOffset": %zu, "byteLength": %zu},
    {"buffer": 0, "byteOffset": %zu, "byteLength": %zu}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": %d, "type": "VEC3", "min": [%g, %g, %g], "max": [%g, %g, %g]},
    {"bufferView": 1, "componentType": 5121, "count": %d, "type": "VEC4"},
    {"bufferView": 2, "componentType": 5126, "count": %d, "type": "VEC4"},
    {"bufferView": 3, "componentType": 5125, "count": %d, "type": "SCALAR"},
    {"bufferView": 4, "componentType": 5126, "count": %zu, "type": "MAT4"}
  ]
})",
                nodes.c_str(), skin.c_str(), bin_name.c_str(), bin.size(), joints_at, joints_at, weights_at - joints_at,
                weights_at, index_at - weights_at, index_at, ibm_at - index_at, ibm_at, bin.size() - ibm_at,
                s.num_vertices(), b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z(), s.num_vertices(),
                s.num_vertices(), 3 * s.num_triangles(), joints.size());
  write_file_atomic(path, gltf);
}

// A skinned glTF whose skeleton holds Mixamo's joints: the elbows and knees
// come from it (the surface shows neither), moved with the body into vgd's
// frame; fingers, hips and shoulders are not taken. The rig's elbows sit at
// half the arm, not at the 56 % the surface rule would give.
// The rig's shoulders and wrists are a few cm off where the surface puts
// them (its shoulder joint 3 cm inside the chest's half-width, its wrist at
// the thinnest slice): the arms follow the rig's.
TEST(ImportedBodySkinned, ArmJointsAndKneesComeFromTheSkeleton) {
  const Avatar& body = mannequin('A');
  const auto& s = body.surface;
  const auto dir = test::scratch_dir("avatar_skeleton");
  const BodySegment* la = body.segment("left-arm");
  const BodySegment* ra = body.segment("right-arm");
  ASSERT_TRUE(la && ra);
  const double knee_y = mannequin_landmarks(BodyMeasurements{}).knee;
  const Vec3 up = Vec3::UnitY();
  const std::vector<GltfJoint> joints = {
      {"mixamorig:Hips", Vec3(0, 0.9, 0)},
      {"mixamorig:LeftForeArm", la->start + 0.5 * la->length * la->axis},
      {"mixamorig:RightForeArm", ra->start + 0.5 * ra->length * ra->axis},
      {"mixamorig:LeftHandIndex1", la->start + 1.05 * la->length * la->axis},
      {"mixamorig:LeftLeg", Vec3(0.09, knee_y, 0.0)},
      {"mixamorig:RightLeg", Vec3(-0.09, knee_y, 0.0)},
      {"mixamorig:LeftArm", la->start + 0.03 * la->length * la->axis + 0.02 * up},
      {"mixamorig:RightArm", ra->start + 0.03 * ra->length * ra->axis + 0.02 * up},
      {"mixamorig:LeftHand", la->start + 0.97 * la->length * la->axis},
      {"mixamorig:RightHand", ra->start + 0.97 * ra->length * ra->axis},
      {"mixamorig:LeftShoulder", Vec3(0.03, 1.35, 0.0)},  // the collarbone, beside the neck: not a shoulder joint
  };
  write_skinned_gltf(dir / "rigged.gltf", s, joints, R"("scale": [0.01, 0.01, 0.01])");
  const mesh::Box3 b = mesh::bounding_box(s);
  AvatarReport r;
  const Avatar got = import_avatar(dir / "rigged.gltf", {}, &r);
  ASSERT_TRUE(got.landmarks);
  const BodyLandmarks& l = *got.landmarks;
  const Vec3 shift(-b.centre().x(), -b.min.y(), -b.centre().z());  // the importer's recentring
  ASSERT_TRUE(l.left_arm && l.right_arm);
  EXPECT_TRUE(l.left_arm->elbow_from_skeleton);
  EXPECT_TRUE(l.right_arm->elbow_from_skeleton);
  EXPECT_LT((l.left_arm->elbow - (joints[1].p + shift)).norm(), 1e-3);
  EXPECT_LT((l.right_arm->elbow - (joints[2].p + shift)).norm(), 1e-3);
  EXPECT_NEAR(l.knee, knee_y + shift.y(), 1e-3);
  EXPECT_TRUE(l.left_arm->shoulder_from_skeleton && l.right_arm->shoulder_from_skeleton);
  EXPECT_TRUE(l.left_arm->wrist_from_skeleton && l.right_arm->wrist_from_skeleton);
  EXPECT_LT((l.left_arm->shoulder - (joints[6].p + shift)).norm(), 1e-3);
  EXPECT_LT((l.right_arm->shoulder - (joints[7].p + shift)).norm(), 1e-3);
  EXPECT_LT((l.left_arm->wrist - (joints[8].p + shift)).norm(), 1e-3);
  EXPECT_LT((l.right_arm->wrist - (joints[9].p + shift)).norm(), 1e-3);
  // The arm segments run between the rig's joints.
  for (const auto& [name, shoulder, wrist] : {std::tuple{"left-arm", joints[6].p, joints[8].p},
                                              std::tuple{"right-arm", joints[7].p, joints[9].p}}) {
    const BodySegment* seg = got.segment(name);
    ASSERT_TRUE(seg) << name;
    EXPECT_LT(seg->axis.normalized().cross((wrist - shoulder).normalized()).norm(), 1e-3) << name;
    EXPECT_LT((seg->start - (shoulder + shift)).cross(seg->axis.normalized()).norm(), 1e-3) << name;
  }
  std::string notes;
  for (const auto& n : got.notes) notes += n + "\n";
  EXPECT_NE(notes.find("joints from the file's skeleton: 2 shoulders, 2 elbows, 2 wrists, 2 knees"), std::string::npos)
      << notes;
}

TEST(SkeletonJoints, RigsNamesAreRead) {
  for (const char* n : {"mixamorig:LeftForeArm", "L_Elbow", "lowerarm01.L", "forearm.R", "Bip01 R Forearm", "RightElbow"})
    EXPECT_EQ(skeleton_joint_kind(n), "elbow") << n;
  for (const char* n : {"mixamorig:LeftLeg", "R_Knee", "lowerleg01.L", "shin.L", "Bip01 L Calf"})
    EXPECT_EQ(skeleton_joint_kind(n), "knee") << n;
  for (const char* n : {"mixamorig:LeftHand", "L_Wrist", "wrist.L", "hand.R"}) EXPECT_EQ(skeleton_joint_kind(n), "wrist") << n;
  for (const char* n : {"mixamorig:LeftFoot", "R_Ankle", "foot.L"}) EXPECT_EQ(skeleton_joint_kind(n), "ankle") << n;
  for (const char* n : {"mixamorig:LeftArm", "L_Shoulder", "upperarm01.L", "upper_arm.R", "Bip01 L UpperArm"})
    EXPECT_EQ(skeleton_joint_kind(n), "shoulder") << n;
  for (const char* n : {"mixamorig:LeftUpLeg", "mixamorig:LeftHandIndex1", "mixamorig:LeftShoulder", "shoulder.L",
                        "L_Collar", "Armature", "Hips", "mixamorig:LeftToeBase", "upperleg01.L", "thigh.L",
                        "forearm_twist.L", "upper_arm_twist.L"})
    EXPECT_EQ(skeleton_joint_kind(n), "") << n;
}

// A skeleton whose elbow lies off the arm is not believed.
// Landmarks with a left arm found on the surface, as a skeleton's joints are judged against.
BodyLandmarks left_arm_landmarks() {
  BodyLandmarks l;
  l.crotch = 0.78, l.ankle = 0.1;
  ArmLandmarks arm;
  arm.shoulder = Vec3(0.17, 1.35, 0);
  arm.wrist = Vec3(0.55, 0.95, 0);
  arm.elbow = arm.shoulder + 0.56 * (arm.wrist - arm.shoulder);
  l.left_arm = arm;
  return l;
}

TEST(SkeletonJoints, AnElbowOffTheArmIsLeftOutWithANote) {
  BodyLandmarks l = left_arm_landmarks();
  std::vector<std::string> notes;
  const std::vector<ModelJoint> joints = {{"LeftForeArm", Vec3(0.36, 1.15, 0.2)}, {"LeftLeg", Vec3(0.1, 1.2, 0)}};
  EXPECT_EQ(landmarks_from_skeleton(l, joints, notes), 0);
  EXPECT_FALSE(l.left_arm->elbow_from_skeleton);
  EXPECT_EQ(l.knee, 0.0);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("LeftForeArm left out: 20.0 cm from the arm's axis"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("not between the ankle and the crotch"), std::string::npos) << notes[1];
}

// A shoulder joint at the collarbone's start or a wrist at the fingertips is
// not where the arm ends: left out with a note, the surface's kept.
TEST(SkeletonJoints, AShoulderOrWristFarFromTheArmsEndIsLeftOutWithANote) {
  BodyLandmarks l = left_arm_landmarks();
  const ArmLandmarks arm = *l.left_arm;
  std::vector<std::string> notes;
  const Vec3 d = arm.wrist - arm.shoulder;
  const std::vector<ModelJoint> joints = {{"L_Shoulder", arm.shoulder - 0.4 * d},
                                          {"L_Wrist", arm.wrist + 0.2 * d + Vec3(0, 0, 0.1)}};
  EXPECT_EQ(landmarks_from_skeleton(l, joints, notes), 0);
  EXPECT_FALSE(l.left_arm->shoulder_from_skeleton);
  EXPECT_FALSE(l.left_arm->wrist_from_skeleton);
  EXPECT_EQ(l.left_arm->shoulder, arm.shoulder);
  EXPECT_EQ(l.left_arm->wrist, arm.wrist);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("L_Shoulder left out: 0.0 cm from the arm's axis, -40 % of the way"), std::string::npos)
      << notes[0];
  EXPECT_NE(notes[1].find("L_Wrist left out: 10.0 cm from the arm's axis"), std::string::npos) << notes[1];
}

// A Mixamo-style skinned glTF: the mesh under an armature node that scales by
// 0.01 and turns the body on its back. glTF ignores a skinned mesh's node
// transform; the body is read in its bind pose, at its height.
TEST(ImportedBodySkinned, AnArmatureTransformIsIgnored) {
  const Avatar& body = mannequin('A');
  const auto& s = body.surface;
  const auto dir = test::scratch_dir("avatar_skinned");
  write_skinned_gltf(dir / "skinned.gltf", s, {{"Hips", Vec3::Zero()}},
                     R"("scale": [0.01, 0.01, 0.01], "rotation": [-0.7071068, 0, 0, 0.7071068])");
  const mesh::Box3 b = mesh::bounding_box(s);
  AvatarReport r;
  const Avatar got = import_avatar(dir / "skinned.gltf", {}, &r);
  EXPECT_EQ(r.unit, "m") << r.unit_reason;
  EXPECT_EQ(r.up, "y") << r.up_reason;
  EXPECT_NEAR(r.height, b.size().y(), 0.01);
  std::string notes;
  for (const auto& n : r.notes) notes += n + "\n";
  EXPECT_NE(notes.find("bind pose"), std::string::npos) << notes;

  // The same file without its .bin: the error names the missing file.
  std::filesystem::remove(dir / "skinned.bin");
  try {
    import_avatar(dir / "skinned.gltf");
    ADD_FAILURE() << "a glTF without its .bin was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("skinned.bin"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("vgd can read"), std::string::npos) << e.what();
  }
}

// The error importing `p` gives, as the user reads it.
std::string error_of(const std::filesystem::path& p, const AvatarImportOptions& o = {}) {
  return test::error_of([&] { import_avatar(p, o); }).format();
}

// Nonsense bodies are refused with what is wrong, not imported with a note.
TEST(ImportedBodyErrors, NoHumanBodySaysWhy) {
  const auto& s = mannequin('A').surface;
  const auto dir = test::scratch_dir("avatar_nonsense");
  // 3 mm tall in metres, and 30 m tall in metres: no unit makes them a body.
  write_file_atomic(dir / "tiny.obj", obj_group(s, "body", 0.0018, Eigen::Matrix3d::Identity(), Vec3::Zero(), 1));
  const std::string tiny = error_of(dir / "tiny.obj");
  EXPECT_NE(tiny.find("not a human body"), std::string::npos) << tiny;
  EXPECT_NE(tiny.find("tiny.obj"), std::string::npos) << tiny;
  write_file_atomic(dir / "giant.obj", obj_group(s, "body", 18.0, Eigen::Matrix3d::Identity(), Vec3::Zero(), 1));
  EXPECT_NE(error_of(dir / "giant.obj").find("not a human body"), std::string::npos) << error_of(dir / "giant.obj");
  // A unit given that makes no body.
  AvatarImportOptions mm;
  mm.unit = "mm";
  write_file_atomic(dir / "metres.obj", obj_group(s, "body", 1.0, Eigen::Matrix3d::Identity(), Vec3::Zero(), 1));
  const std::string given = error_of(dir / "metres.obj", mm);
  EXPECT_NE(given.find("the unit given"), std::string::npos) << given;
  // A coordinate that is not a number: named as such, not as a flat mesh.
  std::string text = obj_group(s, "body", 1.0, Eigen::Matrix3d::Identity(), Vec3::Zero(), 1);
  const std::size_t x = text.find("\nv ") + 3;
  text.replace(x, text.find(' ', x) - x, "1e999");  // the first vertex's x overflows to infinity
  write_file_atomic(dir / "infinite.obj", text);
  const std::string inf = error_of(dir / "infinite.obj");
  EXPECT_NE(inf.find("not a finite number"), std::string::npos) << inf;
  EXPECT_EQ(inf.find("flat"), std::string::npos) << inf;
}

// A damaged PLY on which assimp's own post-processing aborts (an assertion in
// its triangulation; found by the fuzz target): assimp reads in a child
// process, so the abort is an error naming the file, and the caller goes on.
TEST(ImportedBodyErrors, AFileThatCrashesAssimpIsAnErrorNotACrash) {
  const auto dir = test::scratch_dir("avatar_assimp_abort");
  const std::string bytes = read_file(test::source_dir() / "tests/fuzz/corpus/avatar/assimp-abort-triangulate.ply");
  write_file_atomic(dir / "damaged.ply", bytes.substr(1));  // the corpus's first byte picks the format
  const std::string e = error_of(dir / "damaged.ply");
  EXPECT_NE(e.find("damaged.ply"), std::string::npos) << e;
  EXPECT_NE(e.find("assimp crashed reading it"), std::string::npos) << e;
  // And the next file reads as ever.
  write_file_atomic(dir / "body.obj", obj_group(mannequin('A').surface, "body", 1.0, Eigen::Matrix3d::Identity(),
                                                Vec3::Zero(), 1));
  EXPECT_NO_THROW(import_avatar(dir / "body.obj"));
}

// A damaged PLY that assimp loops on (found by the fuzz target): the reading
// process is killed at the time limit and the file refused, saying so.
TEST(ImportedBodyErrors, AFileAssimpLoopsOnIsRefusedAtTheTimeLimit) {
  ModelReadOptions o;
  o.time_limit_s = 1.5;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e =
      test::error_of([&] { read_model_file(test::source_dir() / "tests/data/bodies/assimp-loops.ply", o); }).format();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(e.find("assimp-loops.ply"), std::string::npos) << e;
  EXPECT_NE(e.find("had not finished reading it after 1.5 s"), std::string::npos) << e;
  EXPECT_LT(s, 10.0) << "the reader is killed at the limit";
}

}  // namespace
}  // namespace vgd::body
