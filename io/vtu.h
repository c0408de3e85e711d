#pragma once
/// VTK XML UnstructuredGrid (.vtu) files with inline binary arrays, zlib-compressed in blocks
/// and base64-encoded as VTK's own writer does (compressor="vtkZLibDataCompressor"): VTK,
/// ParaView and meshio read them. Shared by every stage that writes cells: fractures,
/// blocks, DDA frames, damage maps.
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace rockmass::io {

/// One named data array: raw little-endian values of a VTK scalar type.
struct VtuArray {
  std::string name;    ///< Name attribute
  std::string type;    ///< VTK type name: Float64, Float32, Int64, Int32 or UInt8
  int components = 1;  ///< values per tuple
  int value_size = 8;  ///< bytes per value (sizeof the C++ type)
  std::string bytes;   ///< the values' bytes (x86-64 and ARM are little-endian)
  /// Names of the components (VTK's ComponentName0.. attributes: ParaView labels them);
  /// empty, or one per component.
  std::vector<std::string> component_names;
};

/// VTK type name of a C++ scalar type.
template <class T>
constexpr const char* vtkTypeName() {
  if constexpr (std::is_same_v<T, double>)
    return "Float64";
  else if constexpr (std::is_same_v<T, float>)
    return "Float32";
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return "Int64";
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return "Int32";
  else {
    static_assert(std::is_same_v<T, std::uint8_t>, "unsupported VTK array type");
    return "UInt8";
  }
}

/// An array named `name` holding `values` (`components` per tuple).
template <class T>
VtuArray makeVtuArray(std::string name, const std::vector<T>& values, int components = 1) {
  VtuArray array;
  array.name = std::move(name);
  array.type = vtkTypeName<T>();
  array.components = components;
  array.value_size = static_cast<int>(sizeof(T));
  array.bytes =
      std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  return array;
}

/// One piece of an unstructured grid.
struct VtuPiece {
  std::vector<double> points;              ///< x, y, z of each point (m)
  std::vector<std::int64_t> connectivity;  ///< point indices of all cells, cell after cell
  std::vector<std::int64_t> offsets;       ///< end of each cell in connectivity
  std::vector<std::uint8_t> types;         ///< VTK cell type of each cell (7 = polygon,
                                           ///< 42 = polyhedron)
  /// Polyhedron cells only (leave both empty otherwise): per cell, the face count, then per
  /// face its point count and point indices (CCW seen from outside); faceoffsets holds the
  /// end of each cell's entry in faces (-1 for a cell that is not a polyhedron).
  std::vector<std::int64_t> faces;
  std::vector<std::int64_t> faceoffsets;
  std::vector<VtuArray> cell_data;   ///< one value (tuple) per cell
  std::vector<VtuArray> point_data;  ///< one value (tuple) per point
  /// Data of the whole grid (VTK's FieldData: ParaView's Information panel; "TimeValue" is
  /// the time ParaView shows); numeric arrays only (meshio cannot read VTK string arrays).
  std::vector<VtuArray> field_data;
};

/// Gathers the points of cells that share vertices: each distinct point (bitwise equal
/// coordinates, -0 as 0) once, in the order first met. The pieces of a cut share their
/// vertices exactly (the cutter rounds each exact vertex once), so the blocks' and faces'
/// files weld 3.7 million piece vertices of the Xiangjiaba model into the points they are.
class PointWelder {
 public:
  explicit PointWelder(std::vector<double>& points) : points_(points) {}
  /// The index of (x, y, z) in the points, appended when new.
  std::int64_t index(double x, double y, double z);

 private:
  struct Key {
    double x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const;
  };
  std::vector<double>& points_;
  std::unordered_map<Key, std::int64_t, KeyHash> index_;
};

/// The .vtu text of `piece`.
std::string formatVtu(const VtuPiece& piece);

/// Standard base64 (RFC 4648) with '=' padding.
std::string base64Encode(std::string_view bytes);

}  // namespace rockmass::io
