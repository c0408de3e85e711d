#include "io/block_mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <memory>
#include <stdexcept>

namespace rockmass::io {

namespace {

/// assimp's exporter id of a format.
const char* exporterId(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj:
      return "objnomtl";  // no .mtl side file: the blocks carry no material colours
    case MeshFormat::Ply:
      return "plyb";
    case MeshFormat::Stl:
      return "stlb";
    case MeshFormat::Glb:
      return "glb2";
  }
  return "";
}

/// One assimp mesh holding a block surface (vertices rounded to float).
aiMesh* makeMesh(const std::string& name, const blocks::TriangleSurface& surface) {
  auto mesh = std::make_unique<aiMesh>();
  mesh->mName = aiString(name);
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mMaterialIndex = 0;
  mesh->mNumVertices = static_cast<unsigned>(surface.vertices.size());
  mesh->mVertices = new aiVector3D[mesh->mNumVertices];
  for (std::size_t i = 0; i < surface.vertices.size(); ++i) {
    const geometry::Vec3& p = surface.vertices[i];
    mesh->mVertices[i] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()),
                                    static_cast<ai_real>(p.z()));
  }
  mesh->mNumFaces = static_cast<unsigned>(surface.triangles.size());
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (std::size_t i = 0; i < surface.triangles.size(); ++i) {
    aiFace& face = mesh->mFaces[i];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(surface.triangles[i][k]);
  }
  return mesh.release();
}

/// The assimp scene: one material, one mesh and one child node per block.
std::unique_ptr<aiScene> makeScene(const blocks::BlockModel& model,
                                   const std::vector<blocks::TriangleSurface>& surfaces) {
  auto scene = std::make_unique<aiScene>();
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1];
  scene->mMaterials[0] = new aiMaterial();
  aiString material_name("rock");
  scene->mMaterials[0]->AddProperty(&material_name, AI_MATKEY_NAME);

  const unsigned n = static_cast<unsigned>(model.blocks.size());
  scene->mNumMeshes = n;
  scene->mMeshes = new aiMesh*[n];
  scene->mRootNode = new aiNode("blocks");
  scene->mRootNode->mNumChildren = n;
  scene->mRootNode->mChildren = new aiNode*[n];
  for (unsigned i = 0; i < n; ++i) {
    const std::string name = "block_" + std::to_string(model.blocks[i].id);
    scene->mMeshes[i] = makeMesh(name, surfaces[i]);
    auto* node = new aiNode(name);
    node->mParent = scene->mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{i};
    scene->mRootNode->mChildren[i] = node;
  }
  return scene;
}

}  // namespace

std::optional<MeshFormat> parseMeshFormat(std::string_view name) {
  if (name == "obj") return MeshFormat::Obj;
  if (name == "ply") return MeshFormat::Ply;
  if (name == "stl") return MeshFormat::Stl;
  if (name == "glb") return MeshFormat::Glb;
  return std::nullopt;
}

std::string meshExtension(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj:
      return "obj";
    case MeshFormat::Ply:
      return "ply";
    case MeshFormat::Stl:
      return "stl";
    case MeshFormat::Glb:
      return "glb";
  }
  return "";
}

std::string formatBlockMesh(const blocks::BlockModel& model, MeshFormat format,
                            std::vector<blocks::TriangleSurface> surfaces) {
  if (surfaces.empty()) {
    for (const blocks::Block& block : model.blocks) surfaces.push_back(blocks::blockSurface(block));
  }
  if (surfaces.size() != model.blocks.size()) {
    throw std::invalid_argument("formatBlockMesh: one surface per block expected");
  }
  const std::unique_ptr<aiScene> scene = makeScene(model, surfaces);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), exporterId(format));
  if (blob == nullptr) {
    throw std::runtime_error("assimp cannot export the blocks as " + meshExtension(format) + ": " +
                             exporter.GetErrorString());
  }
  if (blob->next != nullptr) {
    throw std::runtime_error("assimp exported more than one file for " + meshExtension(format));
  }
  return std::string(static_cast<const char*>(blob->data), blob->size);
}

std::vector<ImportedMesh> readMeshFile(const std::filesystem::path& path) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr) throw std::runtime_error(importer.GetErrorString());
  std::vector<ImportedMesh> meshes;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    ImportedMesh out;
    out.name = mesh->mName.C_Str();
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      out.surface.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines (none in a closed surface)
      out.surface.triangles.push_back({static_cast<int>(face.mIndices[0]),
                                       static_cast<int>(face.mIndices[1]),
                                       static_cast<int>(face.mIndices[2])});
    }
    meshes.push_back(std::move(out));
  }
  return meshes;
}

}  // namespace rockmass::io
