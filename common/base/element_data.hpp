#pragma once
// Values attached to the elements of one numbering: the vertices of the input mesh, the vertices or
// faces of the intrinsic triangulation, or the OpenCL device's locality order of those vertices.
// Every numbering has its own type (as geometry-central's VertexData<T> is tied to one mesh), so a
// field on input vertices cannot be passed where intrinsic values are expected, nor device order
// where domain order is: mixing numberings is a compile error, not a silent permutation. The
// transfers between numberings exist once (common/surface/field_transfer.hpp, opencl/face_records.hpp).
//
// Inside a numbering, elements are plain indices (operator[] takes the index), so numeric loops
// read as before; `values()` gives the raw array for I/O and libraries that want one.
#include <cstddef>
#include <initializer_list>
#include <utility>
#include <vector>

namespace physarum {

template <class Element, class T>
class ElementData {
 public:
  using value_type = T;

  ElementData() = default;
  // `count` elements, each `value`.
  explicit ElementData(std::size_t count, const T& value = T{}) : values_(count, value) {}
  // Takes the values as they are: the caller states which numbering they are in by the type it builds.
  explicit ElementData(std::vector<T> values) : values_(std::move(values)) {}
  explicit ElementData(std::initializer_list<T> values) : values_(values) {}

  std::size_t size() const { return values_.size(); }
  bool empty() const { return values_.empty(); }
  T& operator[](std::size_t i) { return values_[i]; }
  const T& operator[](std::size_t i) const { return values_[i]; }
  auto begin() { return values_.begin(); }
  auto end() { return values_.end(); }
  auto begin() const { return values_.begin(); }
  auto end() const { return values_.end(); }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }
  const T& front() const { return values_.front(); }
  void assign(std::size_t count, const T& value) { values_.assign(count, value); }

  const std::vector<T>& values() const { return values_; }
  std::vector<T>& values() { return values_; }

  bool operator==(const ElementData&) const = default;

 private:
  std::vector<T> values_;
};

// The numberings (tags only).
struct InputVertexTag;      // vertices of the input mesh, in the file's order
struct IntrinsicVertexTag;  // vertices of the intrinsic triangulation = SurfaceDomain vertices
struct IntrinsicFaceTag;    // faces of the intrinsic triangulation = SurfaceDomain faces
struct DeviceVertexTag;     // intrinsic vertices in an OpenCL backend's locality order

template <class T>
using InputVertexData = ElementData<InputVertexTag, T>;
template <class T>
using IntrinsicVertexData = ElementData<IntrinsicVertexTag, T>;
template <class T>
using IntrinsicFaceData = ElementData<IntrinsicFaceTag, T>;
template <class T>
using DeviceVertexData = ElementData<DeviceVertexTag, T>;

}  // namespace physarum
