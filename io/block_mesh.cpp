#include "io/block_mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_gltf.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace rockmass::io {

namespace {

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

/// Appends `values` to the glTF buffer and returns the index of a new buffer view on them
/// (`target`: 34962 vertex attributes, 34963 indices). Every view starts 4-byte aligned.
template <class T>
int addView(tinygltf::Model& gltf, const std::vector<T>& values, int target) {
  std::vector<unsigned char>& data = gltf.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = values.size() * sizeof(T);
  view.target = target;
  data.resize(data.size() + view.byteLength);
  std::memcpy(data.data() + view.byteOffset, values.data(), view.byteLength);
  gltf.bufferViews.push_back(view);
  return static_cast<int>(gltf.bufferViews.size()) - 1;
}

/// Appends the shortest text that reads back as the float `x`.
void appendFloat(std::string& out, float x) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, end);
}

/// Appends the bytes of `value` (little-endian on every platform rockmass builds on).
template <class T>
void appendBytes(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// The binary PLY of the blocks: one vertex and face list, each face with an int property
/// `block` (its block's id), so that a mesh tool can select or colour the blocks. (assimp's
/// PLY exporter writes no face property.)
std::string formatPly(const blocks::BlockModel& model,
                      const std::vector<blocks::TriangleSurface>& surfaces) {
  std::size_t vertices = 0, faces = 0;
  for (const blocks::TriangleSurface& s : surfaces) {
    vertices += s.vertices.size();
    faces += s.triangles.size();
  }
  std::string out =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment rockmass blocks: the outer surface of each block, coordinates in m (x east, y "
      "north, z up); face property block = the block's id\n"
      "element vertex " +
      std::to_string(vertices) +
      "\n"
      "property float x\n"
      "property float y\n"
      "property float z\n"
      "element face " +
      std::to_string(faces) +
      "\n"
      "property list uchar int vertex_indices\n"
      "property int block\n"
      "end_header\n";
  out.reserve(out.size() + 12 * vertices + 17 * faces);
  for (const blocks::TriangleSurface& s : surfaces) {
    for (const geometry::Vec3& p : s.vertices) {
      for (int a = 0; a < 3; ++a) appendBytes(out, static_cast<float>(p[a]));
    }
  }
  std::int32_t base = 0;
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    for (const auto& t : surfaces[b].triangles) {
      appendBytes(out, std::uint8_t{3});
      for (int k = 0; k < 3; ++k) appendBytes(out, static_cast<std::int32_t>(base + t[k]));
      appendBytes(out, static_cast<std::int32_t>(model.blocks[b].id));
    }
    base += static_cast<std::int32_t>(surfaces[b].vertices.size());
  }
  return out;
}

/// The ASCII STL of the blocks: one solid "block_<id>" per block (binary STL has no names;
/// assimp's STL exporter writes all meshes as one solid). Coordinates as 32-bit floats, as
/// binary STL stores them, in their shortest text; facet normals from the triangles.
std::string formatStl(const blocks::BlockModel& model,
                      const std::vector<blocks::TriangleSurface>& surfaces) {
  std::string out;
  for (std::size_t b = 0; b < surfaces.size(); ++b) {
    const std::string name = "block_" + std::to_string(model.blocks[b].id);
    const blocks::TriangleSurface& s = surfaces[b];
    out += "solid " + name + '\n';
    for (const auto& t : s.triangles) {
      const geometry::Vec3& p0 = s.vertices[static_cast<std::size_t>(t[0])];
      const geometry::Vec3 n = (s.vertices[static_cast<std::size_t>(t[1])] - p0)
                                   .cross(s.vertices[static_cast<std::size_t>(t[2])] - p0)
                                   .normalized();
      out += "  facet normal";
      for (int a = 0; a < 3; ++a) {
        out += ' ';
        appendFloat(out, std::isfinite(n[a]) ? static_cast<float>(n[a]) : 0.0f);
      }
      out += "\n    outer loop\n";
      for (int k = 0; k < 3; ++k) {
        out += "      vertex";
        for (int a = 0; a < 3; ++a) {
          out += ' ';
          appendFloat(out, static_cast<float>(s.vertices[static_cast<std::size_t>(t[k])][a]));
        }
        out += '\n';
      }
      out += "    endloop\n  endfacet\n";
    }
    out += "endsolid " + name + '\n';
  }
  return out;
}

/// A base colour per material (glTF's linear RGB), in scene order, repeating.
std::vector<double> materialColour(std::size_t m) {
  static const double kColours[][3] = {{0.55, 0.52, 0.48}, {0.75, 0.75, 0.72}, {0.45, 0.35, 0.25},
                                       {0.30, 0.45, 0.55}, {0.60, 0.45, 0.30}, {0.40, 0.50, 0.35}};
  const double* c = kColours[m % std::size(kColours)];
  return {c[0], c[1], c[2], 1.0};
}

/// The glb of the blocks (tinygltf): one mesh and one node "block_<id>" per block, the
/// node's extras {id, volume, material, pieces}; one glTF material per rock material, named
/// as in the scene; every block node a child of the root node "blocks", which turns the
/// model's z-up (east x, north y) into glTF's y-up (a quarter turn about x: the model's
/// coordinates stay in the meshes, in m).
std::string formatGlb(const blocks::BlockModel& model,
                      const std::vector<blocks::TriangleSurface>& surfaces,
                      const std::vector<std::string>& material_names) {
  tinygltf::Model gltf;
  gltf.asset.version = "2.0";
  gltf.asset.generator = "rockmass";
  gltf.buffers.resize(1);
  // One glTF material per material the blocks use (the validator reports unused ones), in
  // the order of the material indices; "none" for a block with no known material.
  const int materials = static_cast<int>(material_names.size());
  // The block's material index, or `materials` ("none") when the names do not have it.
  const auto slot = [&](const blocks::Block& block) {
    return static_cast<std::size_t>(
        block.material >= 0 && block.material < materials ? block.material : materials);
  };
  std::vector<int> gltf_material(static_cast<std::size_t>(materials) + 1, -1);
  for (const blocks::Block& block : model.blocks) gltf_material[slot(block)] = 0;
  for (int m = 0; m <= materials; ++m) {
    if (gltf_material[static_cast<std::size_t>(m)] < 0) continue;
    gltf_material[static_cast<std::size_t>(m)] = static_cast<int>(gltf.materials.size());
    tinygltf::Material material;
    material.name = m < materials ? material_names[static_cast<std::size_t>(m)] : "none";
    material.pbrMetallicRoughness.baseColorFactor = materialColour(static_cast<std::size_t>(m));
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.9;
    gltf.materials.push_back(material);
  }
  tinygltf::Node root;
  root.name = "blocks";
  const double half = std::sqrt(0.5);
  root.rotation = {-half, 0.0, 0.0, half};  // (x, y, z) -> (x, z, -y): z up becomes y up
  tinygltf::Value::Object root_extras;
  root_extras["units"] = tinygltf::Value(std::string("m"));
  root_extras["up"] = tinygltf::Value(std::string(
      "the meshes hold the model's coordinates (x east, y north, z up); this node turns z up "
      "into glTF's y up"));
  root.extras = tinygltf::Value(root_extras);
  gltf.nodes.push_back(root);
  for (std::size_t i = 0; i < model.blocks.size(); ++i) {
    const blocks::Block& block = model.blocks[i];
    const blocks::TriangleSurface& surface = surfaces[i];
    std::vector<float> positions;
    positions.reserve(3 * surface.vertices.size());
    std::vector<double> low(3, 0.0), high(3, 0.0);
    for (std::size_t v = 0; v < surface.vertices.size(); ++v) {
      for (int a = 0; a < 3; ++a) {
        const float x = static_cast<float>(surface.vertices[v][a]);
        positions.push_back(x);
        low[static_cast<std::size_t>(a)] =
            v == 0 ? x : std::min(low[static_cast<std::size_t>(a)], double{x});
        high[static_cast<std::size_t>(a)] =
            v == 0 ? x : std::max(high[static_cast<std::size_t>(a)], double{x});
      }
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * surface.triangles.size());
    for (const auto& t : surface.triangles) {
      for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(t[k]));
    }
    tinygltf::Accessor position;
    position.bufferView = addView(gltf, positions, TINYGLTF_TARGET_ARRAY_BUFFER);
    position.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    position.count = surface.vertices.size();
    position.type = TINYGLTF_TYPE_VEC3;
    position.minValues = low;
    position.maxValues = high;
    gltf.accessors.push_back(position);
    tinygltf::Accessor index;
    index.bufferView = addView(gltf, indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    index.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    index.count = indices.size();
    index.type = TINYGLTF_TYPE_SCALAR;
    gltf.accessors.push_back(index);

    const std::string name = "block_" + std::to_string(block.id);
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = static_cast<int>(gltf.accessors.size()) - 2;
    primitive.indices = static_cast<int>(gltf.accessors.size()) - 1;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = gltf_material[slot(block)];
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(primitive);
    gltf.meshes.push_back(mesh);

    tinygltf::Node node;
    node.name = name;
    node.mesh = static_cast<int>(gltf.meshes.size()) - 1;
    tinygltf::Value::Object extras;
    extras["id"] = tinygltf::Value(block.id);
    extras["volume"] = tinygltf::Value(block.mass.volume);
    extras["material"] =
        tinygltf::Value(gltf.materials[static_cast<std::size_t>(primitive.material)].name);
    extras["pieces"] = tinygltf::Value(static_cast<int>(block.pieces.size()));
    node.extras = tinygltf::Value(extras);
    gltf.nodes.push_back(node);
    gltf.nodes[0].children.push_back(static_cast<int>(gltf.nodes.size()) - 1);
  }
  tinygltf::Scene scene;
  scene.name = "rockmass blocks";
  scene.nodes = {0};
  gltf.scenes.push_back(scene);
  gltf.defaultScene = 0;
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&gltf, out, /*prettyPrint=*/false, /*writeBinary=*/true)) {
    throw std::runtime_error("tinygltf cannot write the blocks as glb");
  }
  return out.str();
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
                            std::vector<blocks::TriangleSurface> surfaces,
                            const std::vector<std::string>& material_names) {
  if (surfaces.empty()) {
    for (const blocks::Block& block : model.blocks) surfaces.push_back(blocks::blockSurface(block));
  }
  if (surfaces.size() != model.blocks.size()) {
    throw std::invalid_argument("formatBlockMesh: one surface per block expected");
  }
  // glb through tinygltf: assimp's glTF exporter took 8 min 53 s on the Xiangjiaba model's
  // 42 786 blocks (OBJ 31-37 s), and wrote it z-up with no block data.
  switch (format) {
    case MeshFormat::Glb:
      return formatGlb(model, surfaces, material_names);
    case MeshFormat::Ply:
      return formatPly(model, surfaces);
    case MeshFormat::Stl:
      return formatStl(model, surfaces);
    case MeshFormat::Obj:
      break;
  }
  // OBJ through assimp ("objnomtl": no .mtl side file, the blocks carry no material colours).
  const std::unique_ptr<aiScene> scene = makeScene(model, surfaces);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), "objnomtl");
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
