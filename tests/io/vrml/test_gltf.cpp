// glTF binary and OBJ of the final drape: assimp (an independent reader)
// reads the .glb back with every piece and the body, their vertex and face
// counts, colours and texture coordinates; the OBJ reads back with its groups.
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <cstring>
#include <set>

#include "support/test_paths.hpp"
#include "tube_skirt.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/vrml/gltf.hpp"

using namespace vgd;
namespace vrml = vgd::io::vrml;

namespace {

// Distinct particles each piece's faces use: the vertices glTF needs for it.
std::size_t piece_vertices(const vrml::Garment& g, int piece) {
  std::set<int> s;
  for (std::size_t t = 0; t < g.cloth.triangles.size(); ++t)
    if (g.cloth.piece_of(t) == piece) s.insert(g.cloth.triangles[t].begin(), g.cloth.triangles[t].end());
  return s.size();
}

}  // namespace

TEST(Gltf, AssimpReadsBackEveryPieceAndTheBodyWithTheirCounts) {
  const auto g = test::tube_skirt();
  const std::string glb = vrml::glb_bytes(g);
  ASSERT_GT(glb.size(), 20u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 8, 4);
  EXPECT_EQ(length, glb.size());
  EXPECT_EQ(glb.size() % 4, 0u);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(glb.data(), glb.size(), 0, "glb");
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 3u);
  for (int p = 0; p < 2; ++p) {
    const aiMesh* m = scene->mMeshes[p];
    EXPECT_EQ(m->mNumVertices, piece_vertices(g, p)) << p;
    EXPECT_EQ(m->mNumFaces, 96u) << p;
    EXPECT_TRUE(m->HasNormals());
    EXPECT_TRUE(m->HasTextureCoords(0));
  }
  EXPECT_EQ(scene->mMeshes[2]->mNumVertices, g.body->vertices.size());
  EXPECT_EQ(scene->mMeshes[2]->mNumFaces, g.body->triangles.size());
  // Positions are the last frame's; texture coordinates span the piece in metres without a
  // texture (assimp turns glTF's top-down t back into 1 - t: only the span is compared).
  const aiMesh* front = scene->mMeshes[0];
  float umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
  for (unsigned i = 0; i < front->mNumVertices; ++i) {
    const auto& uv = front->mTextureCoords[0][i];
    umin = std::min(umin, uv.x), umax = std::max(umax, uv.x), vmin = std::min(vmin, uv.y), vmax = std::max(vmax, uv.y);
  }
  EXPECT_NEAR(umax - umin, 0.6, 1e-6);
  EXPECT_NEAR(vmax - vmin, 0.5, 1e-6);
  float ymin = 1e9;
  for (unsigned i = 0; i < front->mNumVertices; ++i) ymin = std::min(ymin, front->mVertices[i].y);
  EXPECT_NEAR(ymin, 0.4, 1e-6);
  // BACK's colour is its look's.
  aiColor4D c;
  ASSERT_EQ(scene->mMaterials[scene->mMeshes[1]->mMaterialIndex]->Get(AI_MATKEY_BASE_COLOR, c), AI_SUCCESS);
  EXPECT_NEAR(c.r, 0.8, 1e-6);
  EXPECT_NEAR(c.g, 0.1, 1e-6);
}

TEST(Gltf, ATexturedPieceGetsItsImageAndCoordinatesInRepeats) {
  auto g = test::tube_skirt();
  g.looks[0].texture = "denim.png";
  g.looks[0].repeat_u = g.looks[0].repeat_v = 0.1;
  const std::string glb = vrml::glb_bytes(g);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(glb.data(), glb.size(), 0, "glb");
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  aiString path;
  EXPECT_EQ(scene->mMaterials[scene->mMeshes[0]->mMaterialIndex]->GetTexture(aiTextureType_DIFFUSE, 0, &path),
            AI_SUCCESS);
  EXPECT_STREQ(path.C_Str(), "denim.png");
  float umax = 0;
  for (unsigned i = 0; i < scene->mMeshes[0]->mNumVertices; ++i) umax = std::max(umax, scene->mMeshes[0]->mTextureCoords[0][i].x);
  EXPECT_NEAR(umax, 6.0, 1e-5);  // 0.6 m of fabric, 0.1 m per repeat
}

TEST(DrapeObj, TheObjHasWeldedVerticesMaterialCoordinatesGroupsAndTheBody) {
  const auto g = test::tube_skirt();
  const auto dir = test::scratch_dir("vrml_obj");
  write_file_atomic(dir / "garment.obj", vrml::obj_text(g, "garment.mtl"));
  write_file_atomic(dir / "garment.mtl", vrml::mtl_text(g));
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "garment.obj").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  unsigned faces = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) faces += scene->mMeshes[m]->mNumFaces;
  EXPECT_EQ(faces, 192u + g.body->triangles.size());
  const std::string obj = read_file(dir / "garment.obj");
  auto count = [&](const std::string& prefix) {
    std::size_t n = 0, pos = 0;
    while ((pos = obj.find("\n" + prefix, pos)) != std::string::npos) ++n, ++pos;
    return n;
  };
  EXPECT_EQ(count("v "), 108u + g.body->vertices.size());
  EXPECT_EQ(count("vt "), 126u);
  EXPECT_EQ(count("vn "), 108u);
  EXPECT_EQ(count("g "), 3u);
  EXPECT_NE(obj.find("usemtl BACK"), std::string::npos);
  const std::string mtl = read_file(dir / "garment.mtl");
  EXPECT_NE(mtl.find("newmtl BACK\nKd 0.8 0.1 0.1"), std::string::npos);
}
