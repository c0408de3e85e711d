#pragma once
/// Reading back what io/vtu.cpp writes, independently of the writer: attributes, base64
/// binary DataArrays, zlib-compressed in blocks as VTK's format describes them
/// (vtkZLibDataCompressor; zlib's uncompress inflates). Test-only; the tests must not need
/// VTK or Python.
#include <gtest/gtest.h>
#include <zlib.h>

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

/// The number of base64 characters of `bytes` bytes.
inline std::size_t base64Length(std::size_t bytes) {
  return (bytes + 2) / 3 * 4;
}

/// The bytes of one compressed array text: the base64 UInt64 header [blocks, block size,
/// last partial block size, compressed size of each block], then the base64 blocks.
inline std::string inflateArray(const std::string& body) {
  const std::string first = base64Decode(body.substr(0, base64Length(3 * 8)));
  std::uint64_t head[3];
  std::memcpy(head, first.data(), sizeof head);
  const std::size_t header_chars = base64Length((3 + head[0]) * 8);
  const std::string header = base64Decode(body.substr(0, header_chars));
  std::vector<std::uint64_t> words(3 + head[0]);
  std::memcpy(words.data(), header.data(), words.size() * 8);
  const std::string packed = base64Decode(body.substr(header_chars));
  std::string bytes;
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < head[0]; ++b) {
    const bool partial_last = b + 1 == head[0] && head[2] != 0;
    uLongf size = static_cast<uLongf>(partial_last ? head[2] : head[1]);
    std::string block(size, '\0');
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(block.data()), &size,
                         reinterpret_cast<const Bytef*>(packed.data() + at),
                         static_cast<uLong>(words[3 + b])),
              Z_OK);
    block.resize(size);
    bytes += block;
    at += words[3 + b];
  }
  EXPECT_EQ(at, packed.size());
  return bytes;
}

/// The values of the binary DataArray called `name`: uncompressed (a base64 UInt64 byte
/// count, 12 characters, then the base64 values; the count must agree) or, when the file
/// names vtkZLibDataCompressor, compressed (inflateArray).
inline std::vector<double> dataArray(const std::string& xml, const std::string& name) {
  const std::size_t tag = xml.find("Name=\"" + name + "\"");
  if (tag == std::string::npos) return {};
  const std::size_t tag_start = xml.rfind('<', tag);
  const std::string type = attribute(xml.substr(tag_start), "type");
  EXPECT_EQ(attribute(xml.substr(tag_start), "format"), "binary");
  const std::size_t begin = xml.find('>', tag) + 1;
  std::string body = xml.substr(begin, xml.find("</DataArray>", begin) - begin);
  body.erase(std::remove_if(body.begin(), body.end(), ::isspace), body.end());
  std::string bytes;
  if (attribute(xml, "compressor") == "vtkZLibDataCompressor") {
    bytes = inflateArray(body);
  } else {
    const std::string header = base64Decode(body.substr(0, 12));
    bytes = base64Decode(body.substr(12));
    std::uint64_t size = 0;
    std::memcpy(&size, header.data(), sizeof size);
    EXPECT_EQ(size, bytes.size()) << name;
  }
  if (type == "Float64") return valuesOf<double>(bytes);
  if (type == "Int64") return valuesOf<std::int64_t>(bytes);
  if (type == "Int32") return valuesOf<std::int32_t>(bytes);
  if (type == "UInt8") return valuesOf<std::uint8_t>(bytes);
  ADD_FAILURE() << "unexpected type " << type;
  return {};
}

}  // namespace rockmass::test
