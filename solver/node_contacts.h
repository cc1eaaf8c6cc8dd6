#pragma once
#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera {

/// A node in contact and its tangential spring: key = side << 31 | rank (side 0: a node of body
/// a in b's level set; side 1: a node of b in a's).
struct NodeContact {
  std::uint32_t key;
  Eigen::Vector3d spring;  ///< m
  double energy;           ///< J, stored in this node contact
  double area;             ///< m^2, its effective (projected) area; 0: inside but facing away
};

/// The node contacts of a pair, sorted by key, each quantity in its own array: the contact law
/// reads and writes the springs, areas and energies in place. Read one contact at a time as a
/// NodeContact (by value).
struct NodeContacts {
  std::vector<std::uint32_t> key;
  std::vector<double> springX, springY, springZ;  ///< m
  std::vector<double> energy;                     ///< J
  std::vector<double> area;                       ///< m^2

  std::size_t size() const { return key.size(); }
  bool empty() const { return key.empty(); }
  void clear() { resize(0); }
  /// n contacts (new ones unset; capacity kept).
  void resize(std::size_t n) {
    key.resize(n);
    for (std::vector<double>* v : {&springX, &springY, &springZ, &energy, &area}) v->resize(n);
  }
  void push_back(const NodeContact& c) {
    key.push_back(c.key);
    springX.push_back(c.spring.x());
    springY.push_back(c.spring.y());
    springZ.push_back(c.spring.z());
    energy.push_back(c.energy);
    area.push_back(c.area);
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
