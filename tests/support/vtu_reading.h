#pragma once
/// Reading back what io/vtu.cpp writes, independently of the writer: attributes, base64
/// binary DataArrays. Test-only; the tests must not need VTK or Python.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace rockmass::test {

/// The value of the first attribute `name="..."` in `xml`.
inline std::string attribute(const std::string& xml, const std::string& name) {
  const std::size_t start = xml.find(name + "=\"");
  if (start == std::string::npos) return "";
  const std::size_t value = start + name.size() + 2;
  return xml.substr(value, xml.find('"', value) - value);
}

/// Decodes standard base64 (the test's own decoder, independent of the writer).
inline std::string base64Decode(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned buffer = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    buffer = (buffer << 6) | static_cast<unsigned>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((buffer >> bits) & 0xFF);
    }
  }
  return out;
}

/// Reads `count` values of type T from raw bytes as doubles.
template <class T>
inline std::vector<double> valuesOf(const std::string& bytes) {
  std::vector<double> values(bytes.size() / sizeof(T));
  for (std::size_t i = 0; i < values.size(); ++i) {
    T value;
    std::memcpy(&value, bytes.data() + i * sizeof(T), sizeof(T));
    values[i] = static_cast<double>(value);
  }
  return values;
}

/// The values of the binary DataArray called `name`: a base64 UInt64 byte count (12
/// characters), then the base64 values. Fails the test when the count disagrees.
inline std::vector<double> dataArray(const std::string& xml, const std::string& name) {
  const std::size_t tag = xml.find("Name=\"" + name + "\"");
  if (tag == std::string::npos) return {};
  const std::size_t tag_start = xml.rfind('<', tag);
  const std::string type = attribute(xml.substr(tag_start), "type");
  EXPECT_EQ(attribute(xml.substr(tag_start), "format"), "binary");
  const std::size_t begin = xml.find('>', tag) + 1;
  std::string body = xml.substr(begin, xml.find("</DataArray>", begin) - begin);
  body.erase(std::remove_if(body.begin(), body.end(), ::isspace), body.end());
  const std::string header = base64Decode(body.substr(0, 12));
  const std::string bytes = base64Decode(body.substr(12));
  std::uint64_t size = 0;
  std::memcpy(&size, header.data(), sizeof size);
  EXPECT_EQ(size, bytes.size()) << name;
  if (type == "Float64") return valuesOf<double>(bytes);
  if (type == "Int64") return valuesOf<std::int64_t>(bytes);
  if (type == "Int32") return valuesOf<std::int32_t>(bytes);
  if (type == "UInt8") return valuesOf<std::uint8_t>(bytes);
  ADD_FAILURE() << "unexpected type " << type;
  return {};
}

}  // namespace rockmass::test
