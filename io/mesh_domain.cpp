#include "io/mesh_domain.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <array>
#include <map>
#include <vector>

#include "blocks/surface_check.h"
#include "io/input_error.h"

namespace rockmass::io {

MeshDomain readMeshDomain(const std::filesystem::path& mesh, const std::string& scene) {
  const std::string where = scene + ": domain.mesh: " + mesh.filename().string();
  Assimp::Importer importer;
  const aiScene* file = importer.ReadFile(mesh.string(), aiProcess_JoinIdenticalVertices);
  if (file == nullptr) {
    throw InputError(where + " cannot be read: " + importer.GetErrorString());
  }
  MeshDomain domain;
  std::map<std::array<ai_real, 3>, int> welded;
  for (unsigned m = 0; m < file->mNumMeshes; ++m) {
    const aiMesh* part = file->mMeshes[m];
    // Weld across meshes too (JoinIdenticalVertices works within one mesh): a surface split
    // into groups must still close.
    std::vector<int> index(part->mNumVertices);
    for (unsigned v = 0; v < part->mNumVertices; ++v) {
      const aiVector3D& p = part->mVertices[v];
      const auto [it, added] = welded.try_emplace(std::array<ai_real, 3>{p.x, p.y, p.z},
                                                  static_cast<int>(domain.surface.vertices.size()));
      if (added) domain.surface.vertices.emplace_back(p.x, p.y, p.z);
      index[v] = it->second;
    }
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines bound nothing
      std::vector<int> loop;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        loop.push_back(index[face.mIndices[k]]);
      }
      domain.surface.faces.push_back(std::move(loop));
    }
  }
  geometry::Polyhedron triangles;
  if (const auto problem = blocks::surfaceProblem(domain.surface, &triangles)) {
    throw InputError(where + " " + *problem);
  }
  domain.surface = std::move(triangles);
  domain.bounds = geometry::bounds(domain.surface);
  domain.volume = geometry::massProperties(domain.surface).volume;
  return domain;
}

}  // namespace rockmass::io
