// Per-element attribute arrays that grow with the mesh and follow compaction (geometry-central style).
#pragma once
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/binary_io.hpp"
#include "core/handles.hpp"
#include "core/math.hpp"

namespace vdc {

// The name a value type is stored under in binary files; every type an attribute holds has one.
template <class T>
struct AttributeType;
template <>
struct AttributeType<double> {
  static constexpr const char* name = "f64";
};
template <>
struct AttributeType<int32_t> {
  static constexpr const char* name = "i32";
};
template <>
struct AttributeType<Vec2> {
  static constexpr const char* name = "vec2";
};
template <>
struct AttributeType<Vec3> {
  static constexpr const char* name = "vec3";
};
template <>
struct AttributeType<Mat2> {
  static constexpr const char* name = "mat2";
};

// Attributes of these types can be written to binary files (checkpoints); others (kept only
// while a program runs) cannot.
template <class T>
concept StorableAttribute = requires { AttributeType<T>::name; };

class AttributeBase {
 public:
  virtual ~AttributeBase() = default;
  virtual void resize(std::size_t n) = 0;
  // Keep element new_to_old[i] at position i, drop the rest.
  virtual void permute(const std::vector<int32_t>& new_to_old) = 0;
  virtual std::unique_ptr<AttributeBase> clone() const = 0;
  // Gives element `to` the value of element `from` (a tombstoned `from` still holds its value).
  virtual void copy_element(std::size_t from, std::size_t to) = 0;
  // Type name, default value and values, for AttributeSet::read.
  virtual void write(BinaryWriter& out) const = 0;
};

template <class Tag, class T>
class Attribute final : public AttributeBase {
 public:
  explicit Attribute(T default_value) : default_(std::move(default_value)) {}
  T& operator[](Handle<Tag> h) { return data_[static_cast<std::size_t>(h.idx)]; }
  const T& operator[](Handle<Tag> h) const { return data_[static_cast<std::size_t>(h.idx)]; }
  std::size_t size() const { return data_.size(); }
  const T& default_value() const { return default_; }
  std::vector<T>& raw() { return data_; }
  const std::vector<T>& raw() const { return data_; }

  void resize(std::size_t n) override { data_.resize(n, default_); }
  void permute(const std::vector<int32_t>& new_to_old) override {
    std::vector<T> out;
    out.reserve(new_to_old.size());
    for (int32_t old : new_to_old) out.push_back(data_[static_cast<std::size_t>(old)]);
    data_ = std::move(out);
  }
  std::unique_ptr<AttributeBase> clone() const override { return std::make_unique<Attribute>(*this); }
  void copy_element(std::size_t from, std::size_t to) override { data_[to] = data_[from]; }
  void write(BinaryWriter& out) const override {
    if constexpr (StorableAttribute<T>) {
      out.string(AttributeType<T>::name);
      out.value(default_);
      out.array(data_);
    } else {
      throw std::logic_error("an attribute of a type with no AttributeType name cannot be written");
    }
  }

 private:
  T default_;
  std::vector<T> data_;
};

// The named attributes of one element kind. Owned by the mesh, which resizes and permutes them.
template <class Tag>
class AttributeSet {
 public:
  AttributeSet() = default;
  AttributeSet(const AttributeSet& other) : size_(other.size_) {
    for (const auto& [name, a] : other.attrs_) attrs_.emplace(name, a->clone());
  }
  AttributeSet& operator=(const AttributeSet& other) {
    if (this != &other) *this = AttributeSet(other);
    return *this;
  }
  AttributeSet(AttributeSet&&) noexcept = default;
  AttributeSet& operator=(AttributeSet&&) noexcept = default;

  template <class T>
  Attribute<Tag, T>& add(const std::string& name, T default_value) {
    if (attrs_.count(name)) throw std::logic_error("attribute '" + name + "' already exists");
    auto a = std::make_unique<Attribute<Tag, T>>(std::move(default_value));
    a->resize(size_);
    auto& ref = *a;
    attrs_.emplace(name, std::move(a));
    return ref;
  }
  template <class T>
  Attribute<Tag, T>& get(const std::string& name) {
    auto it = attrs_.find(name);
    if (it == attrs_.end()) throw std::logic_error("no attribute '" + name + "'");
    auto* a = dynamic_cast<Attribute<Tag, T>*>(it->second.get());
    if (!a) throw std::logic_error("attribute '" + name + "' has another type");
    return *a;
  }
  template <class T>
  const Attribute<Tag, T>& get(const std::string& name) const {
    return const_cast<AttributeSet*>(this)->get<T>(name);
  }
  template <class T>
  Attribute<Tag, T>& get_or_add(const std::string& name, T default_value) {
    return has(name) ? get<T>(name) : add<T>(name, std::move(default_value));
  }
  bool has(const std::string& name) const { return attrs_.count(name) > 0; }
  void remove(const std::string& name) { attrs_.erase(name); }

  std::size_t size() const { return size_; }
  void resize(std::size_t n) {
    size_ = n;
    for (auto& [name, a] : attrs_) a->resize(n);
  }
  void permute(const std::vector<int32_t>& new_to_old) {
    size_ = new_to_old.size();
    for (auto& [name, a] : attrs_) a->permute(new_to_old);
  }
  // Every attribute, by name (AttributeSet::read gives back the same set).
  void write(BinaryWriter& out) const {
    out.value<uint64_t>(attrs_.size());
    for (const auto& [name, a] : attrs_) {
      out.string(name);
      a->write(out);
    }
  }
  // Replaces the attributes with those written by write(); each must have size() values.
  void read(BinaryReader& in) {
    attrs_.clear();
    const auto n = in.value<uint64_t>();
    for (uint64_t i = 0; i < n; ++i) {
      const std::string name = in.string();
      const std::string type = in.string();
      if (type == AttributeType<double>::name) read_values<double>(name, in);
      else if (type == AttributeType<int32_t>::name) read_values<int32_t>(name, in);
      else if (type == AttributeType<Vec2>::name) read_values<Vec2>(name, in);
      else if (type == AttributeType<Vec3>::name) read_values<Vec3>(name, in);
      else if (type == AttributeType<Mat2>::name) read_values<Mat2>(name, in);
      else in.fail("attribute '" + name + "' has an unknown type '" + type + "'");
    }
  }
  // Every attribute of element `to` takes the value of element `from`.
  void copy(Handle<Tag> from, Handle<Tag> to) {
    for (auto& [name, a] : attrs_) a->copy_element(static_cast<std::size_t>(from.idx), static_cast<std::size_t>(to.idx));
  }

 private:
  template <class T>
  void read_values(const std::string& name, BinaryReader& in) {
    const T default_value = in.value<T>();
    std::vector<T> values = in.array<T>();
    if (values.size() != size_) in.fail("attribute '" + name + "' has " + std::to_string(values.size()) + " values for " + std::to_string(size_) + " elements");
    if (attrs_.count(name)) in.fail("attribute '" + name + "' appears twice");
    add<T>(name, default_value).raw() = std::move(values);
  }

  std::size_t size_ = 0;
  std::map<std::string, std::unique_ptr<AttributeBase>> attrs_;
};

}  // namespace vdc
