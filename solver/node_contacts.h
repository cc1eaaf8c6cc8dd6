#pragma once
#include "solver/pair_state.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera {

/// The precision of a node contact's state and of the contact law that updates it: float, eight
/// SIMD lanes on AVX2 where double has four. Each input is computed in double (positions, depths,
/// normals, velocities) and rounded once; the law's products and sums then carry a relative
/// error of about 1e-7 per contact, far below what the answers resolve (docs/physics.md,
/// "Precision of the contact law"). A pair's sums are added in float, the pairs' in double.
using ContactReal = float;

/// The node contacts of a pair, sorted by key, each quantity in its own array: the contact law
/// reads and writes the springs, areas and energies in place. Read one contact at a time as a
/// NodeContact (by value). The state arrays run on to a whole number of kLawBlock entries, the
/// entries past size() all 0, so that the law runs over whole blocks of SIMD lanes.
struct NodeContacts {
  static constexpr std::size_t kLawBlock = 8;  ///< eight ContactReal lanes (AVX2)
  /// n rounded up to whole blocks.
  static std::size_t padded(std::size_t n) { return (n + kLawBlock - 1) / kLawBlock * kLawBlock; }

  std::vector<std::uint32_t> key;
  std::vector<ContactReal> springX, springY, springZ;  ///< m
  std::vector<ContactReal> energy;                     ///< J
  std::vector<ContactReal> area;                       ///< m^2

  std::size_t size() const { return key.size(); }
  bool empty() const { return key.empty(); }
  void clear() { resize(0); }
  /// n contacts (new ones unset; capacity kept), the padding past them 0.
  void resize(std::size_t n) {
    key.resize(n);
    for (std::vector<ContactReal>* v : {&springX, &springY, &springZ, &energy, &area}) {
      v->resize(padded(n));
      std::fill(v->begin() + static_cast<std::ptrdiff_t>(n), v->end(), ContactReal(0));
    }
  }
  /// A contact at the end, its values rounded to ContactReal (exact for values read from one).
  void push_back(const NodeContact& c) {
    resize(size() + 1);
    set(size() - 1, c);
  }
  /// These contacts in place of the ones held, in their order.
  void assign(const std::vector<NodeContact>& contacts) {
    resize(contacts.size());
    for (std::size_t i = 0; i < contacts.size(); ++i) set(i, contacts[i]);
  }
  /// Contact i set to c, its values rounded to ContactReal.
  void set(std::size_t i, const NodeContact& c) {
    const auto real = [](double v) { return static_cast<ContactReal>(v); };
    key[i] = c.key;
    springX[i] = real(c.spring.x());
    springY[i] = real(c.spring.y());
    springZ[i] = real(c.spring.z());
    energy[i] = real(c.energy);
    area[i] = real(c.area);
  }
  NodeContact operator[](std::size_t i) const {
    return {key[i], Eigen::Vector3d(springX[i], springY[i], springZ[i]), energy[i], area[i]};
  }

  /// Iteration by value: for (const NodeContact& c : contacts).
  struct Iterator {
    const NodeContacts* contacts;
    std::size_t i;
    NodeContact operator*() const { return (*contacts)[i]; }
    Iterator& operator++() {
      ++i;
      return *this;
    }
    bool operator!=(const Iterator& other) const { return i != other.i; }
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, size()}; }
};

}  // namespace tessera
