// The vgd_assimp module: the only code of vgd that includes assimp. Built as a
// shared object of its own and opened by model_file.cpp on first use.
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdint>

#include "module_api.hpp"

namespace vgd::body::assimp_module {
namespace {

// Merges every mesh of the node tree, each with its accumulated transform
// (none for a skinned mesh when `bind_pose`).
void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, bool bind_pose, ModelFile& out) {
  const aiMatrix4x4 t = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* m = scene->mMeshes[node->mMeshes[i]];
    const int base = out.surface.num_vertices();
    const int first_triangle = out.surface.num_triangles();
    const bool skinned = m->HasBones();
    const aiMatrix4x4 mt = skinned && bind_pose ? aiMatrix4x4() : t;
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D p = mt * m->mVertices[v];
      out.surface.vertices.emplace_back(p.x, p.y, p.z);
    }
    // The bones' bind-pose origins, moved as the vertices are.
    for (unsigned b = 0; b < m->mNumBones; ++b) {
      const aiBone* bone = m->mBones[b];
      const std::string name = bone->mName.C_Str();
      bool seen = false;
      for (const auto& j : out.joints) seen = seen || j.name == name;
      if (seen) continue;
      aiMatrix4x4 bind = bone->mOffsetMatrix;  // mesh space -> bone space
      bind.Inverse();
      const aiVector3D p = mt * (bind * aiVector3D(0, 0, 0));
      out.joints.push_back({name, Eigen::Vector3d(p.x, p.y, p.z)});
    }
    bool any = false;
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) {
        ++out.dropped;
        continue;
      }
      out.surface.triangles.push_back({base + static_cast<int>(face.mIndices[0]),
                                       base + static_cast<int>(face.mIndices[1]),
                                       base + static_cast<int>(face.mIndices[2])});
      any = true;
    }
    if (any) {
      ModelMesh mm;
      mm.name = m->mName.C_Str();
      mm.node = node->mName.C_Str();
      mm.first_vertex = base;
      mm.vertices = static_cast<int>(m->mNumVertices);
      mm.first_triangle = first_triangle;
      mm.triangles = out.surface.num_triangles() - first_triangle;
      mm.skinned = skinned;
      out.meshes.push_back(std::move(mm));
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], t, bind_pose, out);
}

void read_metadata(const aiScene* s, ModelFile& out) {
  if (!s->mMetaData) return;
  for (unsigned i = 0; i < s->mMetaData->mNumProperties; ++i) {
    const aiMetadataEntry& e = s->mMetaData->mValues[i];
    const std::string key = s->mMetaData->mKeys[i].C_Str();
    switch (e.mType) {
      case AI_INT32: out.metadata[key] = *static_cast<const int32_t*>(e.mData); break;
      case AI_UINT64: out.metadata[key] = static_cast<double>(*static_cast<const uint64_t*>(e.mData)); break;
      case AI_FLOAT: out.metadata[key] = *static_cast<const float*>(e.mData); break;
      case AI_DOUBLE: out.metadata[key] = *static_cast<const double*>(e.mData); break;
      default: break;
    }
  }
}

std::string read(const std::filesystem::path& path, const ModelReadOptions& options, ModelFile& out) {
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, 0);
  // Validation first: some importers hand back scenes with null nodes or
  // meshes (two RAW files of assimp's own test models crashed the reader).
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                                              aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) {
    const std::string why = importer.GetErrorString();
    return why.empty() ? "assimp gave no scene" : why;
  }
  collect(scene, scene->mRootNode, aiMatrix4x4(), options.bind_pose, out);
  read_metadata(scene, out);
  return "";
}

std::string write(const mesh::SurfaceMesh& s, const std::vector<Eigen::Vector3d>& normals,
                  const std::filesystem::path& path, const std::string& format_id) {
  aiScene scene;
  scene.mRootNode = new aiNode();
  scene.mRootNode->mName = "avatar";
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh* m = scene.mMeshes[0];
  m->mName = "body";
  m->mMaterialIndex = 0;
  m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m->mNumVertices = static_cast<unsigned>(s.vertices.size());
  m->mVertices = new aiVector3D[m->mNumVertices];
  m->mNormals = new aiVector3D[m->mNumVertices];
  for (unsigned i = 0; i < m->mNumVertices; ++i) {
    const auto& p = s.vertices[i];
    const auto& n = normals[i];
    m->mVertices[i] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
    m->mNormals[i] = aiVector3D(static_cast<ai_real>(n.x()), static_cast<ai_real>(n.y()), static_cast<ai_real>(n.z()));
  }
  m->mNumFaces = static_cast<unsigned>(s.triangles.size());
  m->mFaces = new aiFace[m->mNumFaces];
  for (unsigned f = 0; f < m->mNumFaces; ++f) {
    m->mFaces[f].mNumIndices = 3;
    m->mFaces[f].mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) m->mFaces[f].mIndices[k] = static_cast<unsigned>(s.triangles[f][k]);
  }
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  Assimp::Exporter exporter;
  if (exporter.Export(&scene, format_id.c_str(), path.string()) != AI_SUCCESS) return exporter.GetErrorString();
  return "";
}

const Api kApi{kApiVersion, &read, &write};

}  // namespace
}  // namespace vgd::body::assimp_module

extern "C" __attribute__((visibility("default"))) const vgd::body::assimp_module::Api* vgd_assimp_module_api() {
  return &vgd::body::assimp_module::kApi;
}
