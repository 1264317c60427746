// Index handles for mesh elements: typed, so a face index cannot be used as a node index.
#pragma once
#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace vdc {

template <class Tag>
struct Handle {
  int32_t idx = -1;
  constexpr Handle() = default;
  constexpr explicit Handle(int32_t i) : idx(i) {}
  constexpr bool valid() const { return idx >= 0; }
  friend constexpr bool operator==(Handle, Handle) = default;
  friend constexpr auto operator<=>(Handle, Handle) = default;
};

struct NodeTag {};
struct VertTag {};
struct EdgeTag {};
struct FaceTag {};
using NodeId = Handle<NodeTag>;
using VertId = Handle<VertTag>;
using EdgeId = Handle<EdgeTag>;
using FaceId = Handle<FaceTag>;

}  // namespace vdc

template <class Tag>
struct std::hash<vdc::Handle<Tag>> {
  std::size_t operator()(vdc::Handle<Tag> h) const noexcept { return std::hash<int32_t>()(h.idx); }
};
