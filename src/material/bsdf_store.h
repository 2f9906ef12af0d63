// BSDFs built once and looked up later, one array per concrete BSDF type:
// a light vertex's BSDF is built (its textures evaluated) when the vertex
// is found, and every eye vertex that connects to it reads it from here
// instead of building it again. A BsdfRef names the array and the entry,
// so a lookup is a switch over the types, never a virtual call.
#pragma once

#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "material/coated_conductor_bsdf.h"
#include "material/coated_diffuse_bsdf.h"
#include "material/conductor_bsdf.h"
#include "material/dielectric_bsdf.h"
#include "material/diffuse_bsdf.h"
#include "material/diffuse_transmission_bsdf.h"
#include "material/hair_bsdf.h"
#include "material/fourier_bsdf.h"
#include "material/measured_bsdf.h"
#include "material/thin_dielectric_bsdf.h"

namespace lantern {

struct BsdfRef {
  static constexpr uint8_t kNone = 0xFF;
  uint8_t type = kNone;  // the array: a position in BsdfStore's type list
  uint32_t index = 0;    // the entry in it
  bool valid() const { return type != kNone; }
};

class BsdfStore {
 public:
  template <class BSDF>
  BsdfRef push(const BSDF& bsdf) {
    auto& v = std::get<std::vector<BSDF>>(pools_);
    v.push_back(bsdf);
    return {uint8_t(type_index<BSDF>(std::make_index_sequence<kTypes>{})), uint32_t(v.size() - 1)};
  }
  // Calls fn(bsdf) with the stored BSDF, as its concrete type.
  template <class Fn>
  void visit(BsdfRef r, Fn&& fn) const {
    visit_each(r, fn, std::make_index_sequence<kTypes>{});
  }
  void clear() {
    std::apply([](auto&... v) { (v.clear(), ...); }, pools_);
  }
  size_t memory_bytes() const {
    return std::apply([](const auto&... v) { return (size_t(0) + ... + (v.capacity() * sizeof(v.front()))); }, pools_);
  }

 private:
  using Pools =
      std::tuple<std::vector<DiffuseBSDF>, std::vector<ConductorBSDF>, std::vector<DielectricBSDF>,
                 std::vector<CoatedDiffuseBSDF>, std::vector<CoatedConductorBSDF>, std::vector<DiffuseTransmissionBSDF>,
                 std::vector<ThinDielectricBSDF>, std::vector<HairBSDF>, std::vector<MeasuredBSDF>,
                 std::vector<FourierBSDF>>;
  static constexpr size_t kTypes = std::tuple_size_v<Pools>;

  template <class BSDF, size_t... I>
  static constexpr size_t type_index(std::index_sequence<I...>) {
    return ((std::is_same_v<std::vector<BSDF>, std::tuple_element_t<I, Pools>> ? I : 0) + ...);
  }
  template <class Fn, size_t... I>
  void visit_each(BsdfRef r, Fn& fn, std::index_sequence<I...>) const {
    (void)((r.type == I ? (fn(std::get<I>(pools_)[r.index]), true) : false) || ...);
  }

  Pools pools_;
};

}  // namespace lantern
