#pragma once
/// VTK XML UnstructuredGrid (.vtu) files with inline binary arrays (base64), the form
/// ParaView reads fastest and stores in about half the bytes of ASCII. Shared by every
/// stage that writes cells: fractures, blocks, DDA frames.
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace rockmass::io {

/// One named data array: raw little-endian values of a VTK scalar type.
struct VtuArray {
  std::string name;    ///< Name attribute
  std::string type;    ///< VTK type name: Float64, Float32, Int64, Int32 or UInt8
  int components = 1;  ///< values per tuple
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
};

/// The .vtu text of `piece`.
std::string formatVtu(const VtuPiece& piece);

/// Standard base64 (RFC 4648) with '=' padding.
std::string base64Encode(std::string_view bytes);

}  // namespace rockmass::io
