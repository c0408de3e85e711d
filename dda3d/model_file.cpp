#include "dda3d/model_file.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace rockmass::dda3d {

namespace {

constexpr char kMagic[] = "rockmass-dda-model 2\n";

/// Appends plain values to a byte string.
class Writer {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* bytes = reinterpret_cast<const char*>(&value);
    data_.append(bytes, sizeof(T));
  }
  void put(const geometry::Vec3& v) {
    for (int k = 0; k < 3; ++k) put(v[k]);
  }
  void put(const std::string& text) {
    put(static_cast<std::uint64_t>(text.size()));
    data_.append(text);
  }
  template <class T>
  void putVector(const std::vector<T>& values) {
    put(static_cast<std::uint64_t>(values.size()));
    for (const T& v : values) put(v);
  }
  const std::string& data() const { return data_; }

 private:
  std::string data_;
};

/// Reads the values a Writer wrote, checking that each lies within the data.
class Reader {
 public:
  Reader(const std::string& data, std::string name) : data_(data), name_(std::move(name)) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    if (data_.size() - at_ < sizeof(T)) fail("ends early");
    T value;
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  geometry::Vec3 vec3() {
    geometry::Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = get<double>();
    return v;
  }
  std::string text() {
    const std::size_t n = count(1);
    std::string out = data_.substr(at_, n);
    at_ += n;
    return out;
  }
  /// A count of items of at least `item_bytes` each that the rest of the data can hold.
  std::size_t count(std::size_t item_bytes) {
    const auto n = get<std::uint64_t>();
    if (n > (data_.size() - at_) / item_bytes) fail("holds a count larger than its data");
    return static_cast<std::size_t>(n);
  }
  template <class T>
  std::vector<T> vector() {
    std::vector<T> out(count(sizeof(T)));
    for (T& v : out) v = get<T>();
    return out;
  }
  bool done() const { return at_ == data_.size(); }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(name_ + ": not a DDA model file of this version (" + what + ")");
  }

 private:
  const std::string& data_;
  std::string name_;
  std::size_t at_ = 0;
};

void putPolyhedron(Writer& w, const geometry::Polyhedron& p) {
  w.put(static_cast<std::uint64_t>(p.vertices.size()));
  for (const geometry::Vec3& v : p.vertices) w.put(v);
  w.put(static_cast<std::uint64_t>(p.faces.size()));
  for (const std::vector<int>& face : p.faces) w.putVector(face);
}

geometry::Polyhedron getPolyhedron(Reader& r) {
  geometry::Polyhedron p;
  p.vertices.resize(r.count(24));
  for (geometry::Vec3& v : p.vertices) v = r.vec3();
  p.faces.resize(r.count(8));
  for (std::vector<int>& face : p.faces) {
    face = r.vector<int>();
    for (int v : face) {
      if (v < 0 || static_cast<std::size_t>(v) >= p.vertices.size())
        r.fail("a face names no vertex");
    }
  }
  return p;
}

std::string serialized(const DdaModel& m) {
  Writer w;
  w.put(static_cast<std::uint64_t>(m.blocks.size()));
  for (const DdaBlock& b : m.blocks) {
    w.put(static_cast<std::uint64_t>(b.pieces.size()));
    for (const geometry::Polyhedron& p : b.pieces) putPolyhedron(w, p);
    w.put(b.material);
    w.put(static_cast<std::uint8_t>(b.fixed));
    w.put(b.structure);
    w.put(static_cast<std::uint64_t>(b.face_joints.size()));
    for (const std::vector<int>& row : b.face_joints) w.putVector(row);
    w.put(static_cast<std::uint8_t>(b.contact_point_spacing.has_value()));
    w.put(b.contact_point_spacing.value_or(0.0));
    for (int k = 0; k < 6; ++k) w.put(b.initial_stress[k]);
    w.put(b.initial_velocity);
    w.put(b.initial_angular_velocity);
  }
  w.put(static_cast<std::uint64_t>(m.materials.size()));
  for (const DdaMaterial& x : m.materials) w.put(x.density), w.put(x.young), w.put(x.poisson);
  w.put(static_cast<std::uint64_t>(m.joints.size()));
  for (const DdaJoint& j : m.joints) {
    w.put(j.friction), w.put(j.cohesion), w.put(j.tensile_strength);
    w.put(static_cast<std::uint8_t>(j.model));
  }
  w.put(m.default_joint);
  w.put(m.gravity);
  w.put(m.seismic);
  w.put(static_cast<std::uint64_t>(m.monitors.size()));
  for (const DdaMonitor& x : m.monitors) w.put(x.name), w.put(x.point), w.put(x.block);
  w.put(static_cast<std::uint64_t>(m.point_loads.size()));
  for (const DdaPointLoad& x : m.point_loads) w.put(x.block), w.put(x.point), w.put(x.force);
  w.put(static_cast<std::uint64_t>(m.fixed_points.size()));
  for (const DdaFixedPoint& x : m.fixed_points) {
    w.put(x.block), w.put(x.point), w.put(x.direction);
    w.put(static_cast<std::uint8_t>(x.current.has_value()));
    w.put(x.current.value_or(x.point));
  }
  w.put(static_cast<std::uint64_t>(m.pressures.size()));
  for (const DdaPressure& x : m.pressures) {
    w.put(x.block), w.put(x.piece), w.put(x.face), w.put(x.level), w.put(x.unit_weight);
    w.put(static_cast<std::uint8_t>(x.uplift)), w.put(static_cast<std::uint8_t>(x.pore));
    w.put(x.head_gradient);
    w.put(static_cast<std::uint64_t>(x.within.size()));
    for (const HalfSpace& h : x.within) w.put(h.normal), w.put(h.offset);
  }
  w.put(static_cast<std::uint64_t>(m.hydrodynamic.size()));
  for (const DdaHydrodynamicPressure& x : m.hydrodynamic) {
    w.put(x.block), w.put(x.piece), w.put(x.face), w.put(x.level), w.put(x.depth);
    w.put(x.k_h), w.put(x.unit_weight);
  }
  w.put(static_cast<std::uint64_t>(m.bolts.size()));
  for (const DdaBolt& x : m.bolts) {
    w.put(x.block_a), w.put(x.point_a), w.put(x.block_b), w.put(x.point_b);
    w.put(x.stiffness), w.put(x.pretension), w.put(x.yield_force), w.put(x.rupture_force);
    w.put(static_cast<std::uint8_t>(x.broken));
  }
  return w.data();
}

DdaModel deserialized(const std::string& data, const std::string& name) {
  Reader r(data, name);
  DdaModel m;
  m.blocks.resize(r.count(8));
  for (DdaBlock& b : m.blocks) {
    b.pieces.resize(r.count(16));
    for (geometry::Polyhedron& p : b.pieces) p = getPolyhedron(r);
    b.material = r.get<int>();
    b.fixed = r.get<std::uint8_t>() != 0;
    b.structure = r.get<int>();
    b.face_joints.resize(r.count(8));
    for (std::vector<int>& row : b.face_joints) row = r.vector<int>();
    const bool spacing = r.get<std::uint8_t>() != 0;
    const double value = r.get<double>();
    if (spacing) b.contact_point_spacing = value;
    for (int k = 0; k < 6; ++k) b.initial_stress[k] = r.get<double>();
    b.initial_velocity = r.vec3();
    b.initial_angular_velocity = r.vec3();
  }
  m.materials.resize(r.count(24));
  for (DdaMaterial& x : m.materials) {
    x.density = r.get<double>(), x.young = r.get<double>(), x.poisson = r.get<double>();
  }
  m.joints.resize(r.count(25));
  for (DdaJoint& j : m.joints) {
    j.friction = r.get<double>(), j.cohesion = r.get<double>();
    j.tensile_strength = r.get<double>();
    j.model = static_cast<JointModel>(r.get<std::uint8_t>());
  }
  m.default_joint = r.get<int>();
  m.gravity = r.vec3();
  m.seismic = r.vec3();
  m.monitors.resize(r.count(36));
  for (DdaMonitor& x : m.monitors) x.name = r.text(), x.point = r.vec3(), x.block = r.get<int>();
  m.point_loads.resize(r.count(52));
  for (DdaPointLoad& x : m.point_loads)
    x.block = r.get<int>(), x.point = r.vec3(), x.force = r.vec3();
  m.fixed_points.resize(r.count(77));
  for (DdaFixedPoint& x : m.fixed_points) {
    x.block = r.get<int>(), x.point = r.vec3(), x.direction = r.vec3();
    const bool moved = r.get<std::uint8_t>() != 0;
    const geometry::Vec3 current = r.vec3();
    if (moved) x.current = current;
  }
  m.pressures.resize(r.count(62));
  for (DdaPressure& x : m.pressures) {
    x.block = r.get<int>(), x.piece = r.get<int>(), x.face = r.get<int>();
    x.level = r.get<double>(), x.unit_weight = r.get<double>();
    x.uplift = r.get<std::uint8_t>() != 0, x.pore = r.get<std::uint8_t>() != 0;
    x.head_gradient = r.vec3();
    x.within.resize(r.count(32));
    for (HalfSpace& h : x.within) h.normal = r.vec3(), h.offset = r.get<double>();
  }
  m.hydrodynamic.resize(r.count(44));
  for (DdaHydrodynamicPressure& x : m.hydrodynamic) {
    x.block = r.get<int>(), x.piece = r.get<int>(), x.face = r.get<int>();
    x.level = r.get<double>(), x.depth = r.get<double>(), x.k_h = r.get<double>();
    x.unit_weight = r.get<double>();
  }
  m.bolts.resize(r.count(89));
  for (DdaBolt& x : m.bolts) {
    x.block_a = r.get<int>(), x.point_a = r.vec3(), x.block_b = r.get<int>();
    x.point_b = r.vec3(), x.stiffness = r.get<double>(), x.pretension = r.get<double>();
    x.yield_force = r.get<double>(), x.rupture_force = r.get<double>();
    x.broken = r.get<std::uint8_t>() != 0;
  }
  if (!r.done()) r.fail("has bytes after the model");
  return m;
}

}  // namespace

void saveModel(const DdaModel& model, const std::filesystem::path& path) {
  const std::string raw = serialized(model);
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                Z_DEFAULT_COMPRESSION) != Z_OK) {
    throw std::runtime_error("saveModel: zlib could not compress the model");
  }
  packed.resize(packed_size);
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    const std::uint64_t size = raw.size();
    out.write(kMagic, sizeof kMagic - 1);
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(packed.data(), static_cast<std::streamsize>(packed.size()));
    if (!out) throw std::runtime_error("cannot write " + partial.string());
  }
  std::filesystem::rename(partial, path);
}

DdaModel loadModel(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t header = sizeof kMagic - 1 + sizeof(std::uint64_t);
  if (file.size() < header || file.compare(0, sizeof kMagic - 1, kMagic) != 0) {
    throw std::runtime_error(path.string() +
                             ": not a DDA model file (no rockmass-dda-model 2 header)");
  }
  std::uint64_t size = 0;
  std::memcpy(&size, file.data() + sizeof kMagic - 1, sizeof size);
  if (size > (std::uint64_t{1} << 36)) {
    throw std::runtime_error(path.string() + ": not a DDA model file (size field out of range)");
  }
  std::string raw(static_cast<std::size_t>(size), '\0');
  uLongf raw_size = static_cast<uLongf>(size);
  if (uncompress(reinterpret_cast<Bytef*>(raw.data()), &raw_size,
                 reinterpret_cast<const Bytef*>(file.data() + header),
                 static_cast<uLong>(file.size() - header)) != Z_OK ||
      raw_size != size) {
    throw std::runtime_error(path.string() + ": not a DDA model file (corrupt data)");
  }
  return deserialized(raw, path.string());
}

}  // namespace rockmass::dda3d
