#pragma once
/// Block meshes through assimp and tinygltf (`rockmass blocks --mesh-format obj|ply|stl|glb`): one
/// named mesh "block_<id>" per block, its closed outer surface (blocks/block_surface.h) as outward
/// triangles. assimp stays inside block_mesh.cpp.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "blocks/block_model.h"
#include "blocks/block_surface.h"

namespace rockmass::io {

/// The mesh file formats.
enum class MeshFormat { Obj, Ply, Stl, Glb };

/// "obj", "ply", "stl" or "glb" -> the format; nullopt for anything else.
std::optional<MeshFormat> parseMeshFormat(std::string_view name);

/// The file extension without the dot ("obj", "ply", "stl", "glb").
std::string meshExtension(MeshFormat format);

/// The bytes of the block mesh file: one mesh per block named "block_<id>" (in id order)
/// holding blockSurface(block) (coordinates in m, stored as 32-bit floats by every format).
/// OBJ: one `o`/`g` group per block (text); PLY: binary little-endian, all blocks in one
/// vertex/face list (PLY has no mesh names: block i is the i-th range of
/// `surfaces[i].triangles.size()` faces); STL: binary, one solid (no names either, same
/// ranges); glb: glTF 2.0 binary written with tinygltf, one named mesh and node per block,
/// the node's extras {id, volume (m3), material, pieces}, one glTF material per entry of
/// `material_names` (the blocks' material indices), all under a root node "blocks" that
/// turns the model's z up into glTF's y up. `surfaces` must be blockSurface() of each block
/// of `model` in order (pass an empty vector to compute them). Deterministic: the same model
/// gives the same bytes. Throws std::runtime_error when assimp or tinygltf fails.
std::string formatBlockMesh(const blocks::BlockModel& model, MeshFormat format,
                            std::vector<blocks::TriangleSurface> surfaces = {},
                            const std::vector<std::string>& material_names = {});

/// A mesh read back from a file: its name (empty when the format has none) and triangles.
struct ImportedMesh {
  std::string name;
  blocks::TriangleSurface surface;  ///< vertices in m (as stored, float precision)
};

/// Reads a mesh file with assimp, triangulating and joining identical vertices, but keeping
/// the file's meshes apart (no merging post-process). Throws std::runtime_error with
/// assimp's message when the file cannot be read.
std::vector<ImportedMesh> readMeshFile(const std::filesystem::path& path);

}  // namespace rockmass::io
