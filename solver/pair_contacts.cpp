#include "solver/pair_contacts.h"

#include "solver/blended_area.h"
#include "solver/contact_law.h"
#include "solver/cpu_versions.h"
#include "solver/node_contact_law.h"
#include "solver/planes_in_frame.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <utility>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace tessera {

namespace {

// The body-frame box of `other` (a box in its own frame, turned by qO and moved to pO) as seen in
// the frame of a body at (qM, pM): the region where M's nodes can touch it.
Eigen::AlignedBox3d regionInFrame(const Eigen::AlignedBox3d& otherBox, const Eigen::Quaterniond& qO,
                                  const Eigen::Vector3d& pO, const Eigen::Quaterniond& qM, const Eigen::Vector3d& pM) {
  const Eigen::Matrix3d R = (qM.conjugate() * qO).toRotationMatrix();
  const Eigen::Vector3d centre = R * otherBox.center() + qM.conjugate() * (pO - pM);
  const Eigen::Vector3d half = R.cwiseAbs() * (0.5 * otherBox.sizes());
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

// A rigid motion: centroid, velocity, angular velocity (world).
struct Motion {
  Eigen::Vector3d position, velocity, angularVelocity;
};

Motion motionOf(const ContactScene& scene, int i) {
  return {scene.bodies->position[i], scene.bodies->velocity[i], scene.kinematics->angularVelocity[i]};
}

constexpr std::uint32_t kRankMask = (1u << 31) - 1;
constexpr double kSqrt3 = 1.7320508075688772;

// The node contacts of a pair being collected, in key order (side 0, a's nodes in b, then side 1),
// for the contact law: its inputs but the springs (the pair's own NodeContacts hold them, and the
// areas and stored energies) and the velocities (the law takes them from the levers and its side's
// SideMotion), each contact's key and its lever r = x - c_a about body a's centroid (world),
// computed in double and kept as ContactReal. Area 0: a node inside but facing away from the
// contact normal.
struct PairBatch {
  int count = 0;
  /// Of a pair listed by blocks of candidates (convexContacts, levelSetContacts): 0 when every
  /// block's inside lanes were as at the pair's last evaluation (CandidateNodes::inside), so that
  /// its contacts are the last evaluation's, in the same order; above 0 when some block's were
  /// not (or the candidates were rebuilt): the history is merged. -1: listed otherwise (an
  /// obstacle pair): the keys are compared.
  int changed = -1;
  std::vector<std::uint32_t> key;
  std::vector<ContactReal> rx, ry, rz, nx, ny, nz, depth, area;
  std::vector<ContactReal> slopeX, slopeY, slopeZ;  // m^2, d grad a (world; 0 but for a blended area, blended_area.h)
  std::vector<ContactReal> normalSpeed, turned;  // the law's: each contact's v_n and t . s (trialSpring)

  /// Room for n contacts (values unset).
  void reserve(int n) {
    if (static_cast<int>(key.size()) >= n) return;
    const std::size_t size = static_cast<std::size_t>(n + n / 2);
    key.resize(size);
    for (auto* v : {&rx, &ry, &rz, &nx, &ny, &nz, &depth, &area, &slopeX, &slopeY, &slopeZ, &normalSpeed, &turned}) v->resize(size);
  }
  /// A new contact at the end (values unset); its index.
  int append() {
    reserve(count + 1);
    return count++;
  }
  /// The law's padding (lawAndSums): a block of entries from `from` on set to 0.
  void padFrom(int from) {
    constexpr int block = static_cast<int>(NodeContacts::kLawBlock);
    reserve(from + block);
    std::fill_n(key.data() + from, block, 0u);
    for (auto* v : {&rx, &ry, &rz, &nx, &ny, &nz, &depth, &area, &slopeX, &slopeY, &slopeZ, &normalSpeed, &turned})
      std::fill_n(v->data() + from, block, ContactReal(0));
  }
};

// One side of a pair being collected (its nodes on body M, in the other side O): c_M - c_a, and
// the terms of the relative velocity at a node,
//   v_M - v_O + w_M x (x - c_M) - w_O x (x - c_O) = v0 + (w_M - w_O) x r,
// with the lever r = x - c_a and v0 = v_M - v_O + w_O x (c_O - c_a) - w_M x (c_M - c_a).
// blendedArea: the side's nodes have blended areas, whose normal energy changes, as a node moves,
// by the potential's work (not booked as projection; lawAndSums).
struct SideMotion {
  Eigen::Vector3d shift = Eigen::Vector3d::Zero(), v0 = Eigen::Vector3d::Zero(), spin = Eigen::Vector3d::Zero();
  bool blendedArea = false;
};

// Points moved into another frame, x' = R x + t, n at once (SIMD).
TESSERA_CPU_VERSIONS
void transformPoints(int n, const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const double* __restrict x,
                     const double* __restrict y, const double* __restrict z, double* __restrict ox, double* __restrict oy,
                     double* __restrict oz) {
  const double r00 = R(0, 0), r01 = R(0, 1), r02 = R(0, 2), r10 = R(1, 0), r11 = R(1, 1), r12 = R(1, 2), r20 = R(2, 0),
               r21 = R(2, 1), r22 = R(2, 2), tx = t.x(), ty = t.y(), tz = t.z();
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    ox[i] = (r00 * x[i] + r01 * y[i] + r02 * z[i]) + tx;
    oy[i] = (r10 * x[i] + r11 * y[i] + r12 * z[i]) + ty;
    oz[i] = (r20 * x[i] + r21 * y[i] + r22 * z[i]) + tz;
  }
}

// DenseSdf::value of n points at once (SIMD, the corners gathered), as it, and a vector along its
// gradient (DenseSdf::sample's times the voxel size; outside the grid, x less its nearest grid
// point) from the same corner reads; int indices (the grid has fewer than 2^31 nodes).
TESSERA_CPU_VERSIONS
void gridSamples(const DenseSdf& sdf, int n, const double* __restrict x, const double* __restrict y,
                 const double* __restrict z, double* __restrict value, double* __restrict gx, double* __restrict gy,
                 double* __restrict gz) {
  const double x0 = sdf.origin.x(), y0 = sdf.origin.y(), z0 = sdf.origin.z();
  const Eigen::Vector3d top = sdf.upperCorner();
  const double x1 = top.x(), y1 = top.y(), z1 = top.z(), perVoxel = 1.0 / sdf.voxelSize;
  const int ni = sdf.dims[0] - 2, nj = sdf.dims[1] - 2, nk = sdf.dims[2] - 2;
  const int dj = sdf.dims[2], di = sdf.dims[1] * sdf.dims[2];
  const float* __restrict v = sdf.values.data();
#pragma omp simd
  for (int p = 0; p < n; ++p) {
    const double cx = std::min(std::max(x[p], x0), x1), cy = std::min(std::max(y[p], y0), y1), cz = std::min(std::max(z[p], z0), z1);
    const double ux = (cx - x0) * perVoxel, uy = (cy - y0) * perVoxel, uz = (cz - z0) * perVoxel;
    const int i = std::min(static_cast<int>(ux), ni), j = std::min(static_cast<int>(uy), nj), k = std::min(static_cast<int>(uz), nk);
    const double wx = ux - i, wy = uy - j, wz = uz - k;
    const int c = (i * sdf.dims[1] + j) * sdf.dims[2] + k;
    const double c000 = v[c], c001 = v[c + 1], c010 = v[c + dj], c011 = v[c + dj + 1];
    const double c100 = v[c + di], c101 = v[c + di + 1], c110 = v[c + di + dj], c111 = v[c + di + dj + 1];
    const double c00 = c000 + wz * (c001 - c000), c01 = c010 + wz * (c011 - c010);
    const double c10 = c100 + wz * (c101 - c100), c11 = c110 + wz * (c111 - c110);
    const double a = c00 + wy * (c01 - c00), b = c10 + wy * (c11 - c10);
    const double ax = x[p] - cx, ay = y[p] - cy, az = z[p] - cz;
    const double gap = std::sqrt(ax * ax + ay * ay + az * az);
    value[p] = (a + wx * (b - a)) + gap;
    // The trilinear gradient times h (each stage differentiated); outside the grid, away from it.
    const double dy0 = c01 - c00, dy1 = c11 - c10;
    const double dz0 = (c001 - c000) + wy * ((c011 - c010) - (c001 - c000));
    const double dz1 = (c101 - c100) + wy * ((c111 - c110) - (c101 - c100));
    const bool outside = gap > 0;
    gx[p] = outside ? ax : b - a;
    gy[p] = outside ? ay : dy0 + wx * (dy1 - dy0);
    gz[p] = outside ? az : dz0 + wx * (dz1 - dz0);
  }
}

// Four doubles side by side (GCC's vector extension): one AVX2 register, two SSE2 ones; the same
// operations in every lane. (Eight, two AVX2 registers, compile the selects below to scalar code.)
using Lanes = double __attribute__((vector_size(32)));
using LaneMask = long long __attribute__((vector_size(32)));
constexpr int kLanes = 4;

// The candidates of one side of a pair (keys side << 31 | rank): n of them, each array from the
// side's first, padded to whole blocks of four (CandidateNodes).
struct SideCandidates {
  int n = 0;
  const std::uint32_t* key;
  const double *x, *y, *z, *ax, *ay, *az;
  std::uint8_t* inside;  // per block (CandidateNodes::inside), read and written by the listings
};

SideCandidates candidatesOf(PairContacts& pair, std::uint32_t side) {
  CandidateNodes& c = pair.candidates;
  const int at = c.first[side];
  return {c.count[side],    c.key.data() + at, c.x.data() + at,  c.y.data() + at,
          c.z.data() + at, c.ax.data() + at,  c.ay.data() + at, c.az.data() + at,
          c.inside.data() + at / CandidateNodes::kBlock};
}

// The planes of a convex other side (`all` of them, in a side's frame) that can give one of the
// side's candidates c its level set until they are built again (PairContacts::planesKept): phi =
// max_f v_f, and until then each candidate moves less than band / sqrt(3) relative to the other
// side (ContactScene::candidateBand), which changes every v_f, and phi, by less than that. A plane
// more than 2 band below phi at every candidate stays below it; without it, phi and the best
// plane (the first of largest value) are the same, to the bit. With blended areas (blendedArea,
// width c: plane f takes part while v_f >= (1 + c) phi) a plane below (1 + c) phi - (2 + c) band at
// every candidate stays out of every blend (a superset of the planes kept without: phi < band).
std::uint64_t planesNear(const SideCandidates& c, const PlanesInFrame& all, double band, double blendWidth) {
  std::uint64_t kept = 0;
  for (int i = 0; i < c.n; ++i) {
    const Eigen::Vector3d p(c.x[i], c.y[i], c.z[i]);
    int best;
    const double phi = all.phi(p, best);
    for (int f = 0; f < all.count; ++f)
      if (all.value(f, p) >= (1 + blendWidth) * phi - (2 + blendWidth) * band) kept |= 1ull << f;
  }
  return kept;
}

// Four nodes' facingArea with `share` of their areas (ContactParameters::sideAreaShare), from
// their areas projected on the contact plane, -a n_i . n (each node's area a times its outward
// normal n_i: CandidateNodes).
__attribute__((always_inline)) inline void facingSharedArea(Lanes& area, const Lanes& projectedArea, double share) {
  area = share * (projectedArea > 0 ? projectedArea : Lanes{});
}

// The batch's contact arrays from entry `start` on, as the listing functions write them.
struct BatchSlice {
  std::uint32_t* __restrict key;
  ContactReal *__restrict rx, *__restrict ry, *__restrict rz, *__restrict nx, *__restrict ny, *__restrict nz,
      *__restrict depth, *__restrict area, *__restrict slopeX, *__restrict slopeY, *__restrict slopeZ;
  BatchSlice(PairBatch& b, int start)
      : key(b.key.data() + start), rx(b.rx.data() + start), ry(b.ry.data() + start), rz(b.rz.data() + start),
        nx(b.nx.data() + start), ny(b.ny.data() + start), nz(b.nz.data() + start), depth(b.depth.data() + start),
        area(b.area.data() + start), slopeX(b.slopeX.data() + start), slopeY(b.slopeY.data() + start),
        slopeZ(b.slopeZ.data() + start) {}
};

// Lane compaction without branches: for the mask of a block of four lanes (bit j: lane j is kept),
// the lane order that moves the kept lanes to the front, in order (the others follow, unused), for
// four 32-bit keys and for the eight 32-bit words of four doubles (permuted before they are
// rounded to ContactReal: one permutation of a whole register, no widening).
using Keys = std::uint32_t __attribute__((vector_size(16)));
using Words = std::int32_t __attribute__((vector_size(32)));
using Reals = ContactReal __attribute__((vector_size(16)));
using KeyOrder = std::int32_t __attribute__((vector_size(16)));
static_assert(sizeof(ContactReal) == 4, "the listing packs four lanes of 32-bit values");
struct Compaction {
  int keys[16][kLanes];
  int words[16][2 * kLanes];
  constexpr Compaction() : keys{}, words{} {
    for (int mask = 0; mask < 16; ++mask) {
      int kept = 0;
      for (int lane = 0; lane < kLanes; ++lane)
        if (mask >> lane & 1) {
          words[mask][2 * kept] = 2 * lane;
          words[mask][2 * kept + 1] = 2 * lane + 1;
          keys[mask][kept++] = lane;
        }
    }
  }
};
constexpr Compaction kCompaction;

// out = the lanes of v in the order `order` (a variable permutation: GCC's builtin or Clang's).
template <class Vector, class Order>
__attribute__((always_inline)) inline void permute(Vector& out, const Vector& v, const Order& order) {
#ifdef __clang__
  out = __builtin_shufflevector(v, order);
#else
  out = __builtin_shuffle(v, order);
#endif
}

// A side's candidates four at a time (SIMD lanes): the block starting at i (a multiple of four);
// the last block's padding has position NaN (every comparison false: never inside).
struct CandidateLanes {
  static_assert(CandidateNodes::kBlock == kLanes, "candidates are padded to whole blocks of lanes");
  enum Field { X, Y, Z, AX, AY, AZ };
  const SideCandidates& c;
  const double* field[AZ + 1];

  explicit CandidateLanes(const SideCandidates& candidates) : c(candidates), field{c.x, c.y, c.z, c.ax, c.ay, c.az} {}
  void load(Lanes& v, Field f, int i) const { std::memcpy(&v, field[f] + i, sizeof v); }
  /// The nodes' areas times their outward normals.
  void loadAreaNormals(Lanes& ax, Lanes& ay, Lanes& az, int i) const {
    load(ax, AX, i);
    load(ay, AY, i);
    load(az, AZ, i);
  }
  void loadKeys(Keys& keys, int i) const { std::memcpy(&keys, c.key + i, sizeof keys); }
};

// The lane mask of a block's lanes (bit j: lane j is true): each half's sign bits at once
// (SSE2's movmskpd, in every x86-64 CPU; elsewhere lane by lane).
__attribute__((always_inline)) inline int laneBits(const LaneMask& m) {
#ifdef __SSE2__
  __m128d low, high;
  std::memcpy(&low, &m, sizeof low);
  std::memcpy(&high, reinterpret_cast<const char*>(&m) + sizeof low, sizeof high);
  return _mm_movemask_pd(low) | _mm_movemask_pd(high) << 2;
#else
  return static_cast<int>((m[0] & 1) | (m[1] & 2) | (m[2] & 4) | (m[3] & 8));
#endif
}

// Four node contacts (or none, lane by lane) as the listings compute them.
struct ContactLanes {
  Lanes rx, ry, rz, nx, ny, nz, depth, area, slopeX{}, slopeY{}, slopeZ{};
  Keys key;
};

// store(lanes, array) for each quantity of a block of contacts and its array in the batch.
template <class Store>
__attribute__((always_inline)) inline void eachQuantity(const ContactLanes& block, const BatchSlice& out, Store&& store) {
  store(block.rx, out.rx);
  store(block.ry, out.ry);
  store(block.rz, out.rz);
  store(block.nx, out.nx);
  store(block.ny, out.ny);
  store(block.nz, out.nz);
  store(block.depth, out.depth);
  store(block.area, out.area);
  store(block.slopeX, out.slopeX);
  store(block.slopeY, out.slopeY);
  store(block.slopeZ, out.slopeZ);
}

// The lanes of `mask` (laneBits) of a block of contacts, rounded to ContactReal, packed to the
// front and stored in the batch from entry `count` on; the new count. Whole blocks are stored: the
// batch needs room for four entries past the last contact.
__attribute__((always_inline)) inline int storeKept(const ContactLanes& block, int mask, const BatchSlice& out, int count) {
  if (mask == 0xf) {  // every lane kept (most blocks): in order, no permutation
    eachQuantity(block, out, [&](const Lanes& v, ContactReal* to) {
      const Reals rounded = __builtin_convertvector(v, Reals);
      std::memcpy(to + count, &rounded, sizeof rounded);
    });
    std::memcpy(out.key + count, &block.key, sizeof block.key);
    return count + kLanes;
  }
  KeyOrder order;
  std::memcpy(&order, kCompaction.keys[mask], sizeof order);
  Words wordOrder;
  std::memcpy(&wordOrder, kCompaction.words[mask], sizeof wordOrder);
  eachQuantity(block, out, [&](const Lanes& v, ContactReal* to) {  // packed as doubles, then rounded
    Words kept;
    permute(kept, reinterpret_cast<Words>(v), wordOrder);
    const Reals rounded = __builtin_convertvector(reinterpret_cast<Lanes>(kept), Reals);
    std::memcpy(to + count, &rounded, sizeof rounded);
  });
  Keys kept;
  permute(kept, block.key, order);
  std::memcpy(out.key + count, &kept, sizeof kept);
  return count + __builtin_popcount(static_cast<unsigned>(mask));
}

// The contacts of one side's candidates c in a convex other side, listed into the batch from
// entry `start` on; their count. In one pass, four candidates at a time (CandidateLanes):
// phi = max_f (n'_f . p - d'_f) as PlanesInFrame::phi (the first plane of largest value is the
// best; phi and the best plane's normal in M's frame kept in registers across the planes), and
// for the candidates inside (phi < 0), packed to the front of the lanes without branches
// (storeKept): key, lever r = RM p + (c_M - c_a), the best plane's world normal RM n, depth -phi,
// and area: `share` of the node's, projected on the contact plane, -n_i . n (taken in M's frame),
// clipped at 0 (facingSharedArea), or blended over the planes near the nearest (side.blendedArea:
// blendedArea, with its slope). The batch needs room for four entries past the last candidate.
TESSERA_CPU_VERSIONS
int convexContacts(int start, const SideCandidates& c, const PlanesInFrame& planes, const SideMotion& side,
                   const Eigen::Matrix3d& RM, double share, PairBatch& batch) {
  const BatchSlice out(batch, start);
  const double sx = side.shift.x(), sy = side.shift.y(), sz = side.shift.z();
  const double r00 = RM(0, 0), r01 = RM(0, 1), r02 = RM(0, 2), r10 = RM(1, 0), r11 = RM(1, 1), r12 = RM(1, 2), r20 = RM(2, 0),
               r21 = RM(2, 1), r22 = RM(2, 2);
  const CandidateLanes lanes(c);
  int count = 0, changed = 0;
  for (int i = 0; i < c.n; i += kLanes) {
    Lanes x, y, z;
    lanes.load(x, CandidateLanes::X, i);
    lanes.load(y, CandidateLanes::Y, i);
    lanes.load(z, CandidateLanes::Z, i);
    Lanes value = planes.nx[0] * x + planes.ny[0] * y + planes.nz[0] * z - planes.offset[0];
    Lanes nnx = Lanes{} + planes.nx[0], nny = Lanes{} + planes.ny[0], nnz = Lanes{} + planes.nz[0];
    Lanes second = Lanes{} - std::numeric_limits<double>::infinity();  // the second largest value
    for (int f = 1; f < planes.count; ++f) {
      const Lanes v = planes.nx[f] * x + planes.ny[f] * y + planes.nz[f] * z - planes.offset[f];
      const LaneMask higher = v > value;
      const Lanes lower = higher ? value : v;
      second = lower > second ? lower : second;
      value = higher ? v : value;
      nnx = higher ? planes.nx[f] : nnx;
      nny = higher ? planes.ny[f] : nny;
      nnz = higher ? planes.nz[f] : nnz;
    }
    const int mask = laneBits(value < 0);
    changed |= c.inside[i / kLanes] ^ mask;
    c.inside[i / kLanes] = static_cast<std::uint8_t>(mask);
    if (mask == 0) continue;
    ContactLanes b;
    b.nx = r00 * nnx + r01 * nny + r02 * nnz;
    b.ny = r10 * nnx + r11 * nny + r12 * nnz;
    b.nz = r20 * nnx + r21 * nny + r22 * nnz;
    b.rx = (r00 * x + r01 * y + r02 * z) + sx;
    b.ry = (r10 * x + r11 * y + r12 * z) + sy;
    b.rz = (r20 * x + r21 * y + r22 * z) + sz;
    b.depth = -value;
    Lanes ax, ay, az;
    lanes.loadAreaNormals(ax, ay, az, i);
    // Blended where a lane's second plane is within c d of its nearest (t < 1: blendedArea; a
    // little wider, for its rounding); elsewhere the blend is the nearest plane's projection, and
    // 0 slope, which the plain path gives.
    const bool nearSwitch = side.blendedArea && laneBits((value < 0) & (second >= (1 + 1.001 * kAreaBlendWidth) * value)) != 0;
    if (nearSwitch) {
      BlendedArea<Lanes> blend;
      blendedArea(planes, x, y, z, value, nnx, nny, nnz, ax, ay, az, share, blend);
      b.area = blend.area;
      b.slopeX = r00 * blend.slopeX + r01 * blend.slopeY + r02 * blend.slopeZ;
      b.slopeY = r10 * blend.slopeX + r11 * blend.slopeY + r12 * blend.slopeZ;
      b.slopeZ = r20 * blend.slopeX + r21 * blend.slopeY + r22 * blend.slopeZ;
    } else {
      facingSharedArea(b.area, -(ax * nnx + ay * nny + az * nnz), share);
    }
    lanes.loadKeys(b.key, i);
    count = storeKept(b, mask, out, count);
  }
  batch.changed |= changed;
  return count;
}

// ShapeModel::gridLevelSet of n points at once (SIMD), in place, from their grid values and
// vectors along the gradient (gridSamples): inside, the vector made unit, or phi 0 (no contact)
// where it is zero; outside, phi as it is.
TESSERA_CPU_VERSIONS
void gridLevelSets(int n, double* __restrict phi, double* __restrict gx, double* __restrict gy, double* __restrict gz) {
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const double g = std::sqrt(gx[i] * gx[i] + gy[i] * gy[i] + gz[i] * gz[i]);
    const bool usable = g > 0, in = phi[i] < 0;
    const double unit = 1.0 / (usable ? g : 1.0);
    phi[i] = in && !usable ? 0.0 : phi[i];
    gx[i] = gx[i] * unit;
    gy[i] = gy[i] * unit;
    gz[i] = gz[i] * unit;
  }
}

// The candidates of a side found inside a non-convex other side O (their positions o, level set
// phi and unit normal g in O's frame, n of them, with room for four more: phi NaN there) as
// contacts of the batch from entry `start` on; their count. Four candidates at a time
// (CandidateLanes), those inside (phi < 0) packed to the front of the lanes (storeKept): key,
// lever r = RO o + (c_O - c_M) + (c_M - c_a), the world normal RO g, depth -phi, and area: `share`
// of the node's, projected on the contact plane, -(RM n_i) . (RO g), clipped at 0 (facingSharedArea).
TESSERA_CPU_VERSIONS
int levelSetContacts(int start, const SideCandidates& c, const SideMotion& side, const double* __restrict ox,
                     const double* __restrict oy, const double* __restrict oz, const double* __restrict phi,
                     const double* __restrict gx, const double* __restrict gy, const double* __restrict gz,
                     const Eigen::Matrix3d& RO, const Eigen::Matrix3d& RM, const Eigen::Vector3d& offset, double share,
                     PairBatch& batch) {
  const BatchSlice out(batch, start);
  const double o00 = RO(0, 0), o01 = RO(0, 1), o02 = RO(0, 2), o10 = RO(1, 0), o11 = RO(1, 1), o12 = RO(1, 2), o20 = RO(2, 0),
               o21 = RO(2, 1), o22 = RO(2, 2);
  const double m00 = RM(0, 0), m01 = RM(0, 1), m02 = RM(0, 2), m10 = RM(1, 0), m11 = RM(1, 1), m12 = RM(1, 2), m20 = RM(2, 0),
               m21 = RM(2, 1), m22 = RM(2, 2);
  const double tx = offset.x(), ty = offset.y(), tz = offset.z(), sx = side.shift.x(), sy = side.shift.y(),
               sz = side.shift.z();
  const CandidateLanes lanes(c);
  int count = 0, changed = 0;
  for (int i = 0; i < c.n; i += kLanes) {
    Lanes value;
    std::memcpy(&value, phi + i, sizeof value);
    const int mask = laneBits(value < 0);
    changed |= c.inside[i / kLanes] ^ mask;
    c.inside[i / kLanes] = static_cast<std::uint8_t>(mask);
    if (mask == 0) continue;
    Lanes x, y, z, g0, g1, g2;
    std::memcpy(&x, ox + i, sizeof x);
    std::memcpy(&y, oy + i, sizeof y);
    std::memcpy(&z, oz + i, sizeof z);
    std::memcpy(&g0, gx + i, sizeof g0);
    std::memcpy(&g1, gy + i, sizeof g1);
    std::memcpy(&g2, gz + i, sizeof g2);
    ContactLanes b;
    b.rx = ((o00 * x + o01 * y + o02 * z) + tx) + sx;
    b.ry = ((o10 * x + o11 * y + o12 * z) + ty) + sy;
    b.rz = ((o20 * x + o21 * y + o22 * z) + tz) + sz;
    b.nx = o00 * g0 + o01 * g1 + o02 * g2;
    b.ny = o10 * g0 + o11 * g1 + o12 * g2;
    b.nz = o20 * g0 + o21 * g1 + o22 * g2;
    b.depth = -value;
    Lanes ax, ay, az;
    lanes.loadAreaNormals(ax, ay, az, i);
    const Lanes mx = m00 * ax + m01 * ay + m02 * az, my = m10 * ax + m11 * ay + m12 * az, mz = m20 * ax + m21 * ay + m22 * az;
    facingSharedArea(b.area, -(mx * b.nx + my * b.ny + mz * b.nz), share);
    lanes.loadKeys(b.key, i);
    count = storeKept(b, mask, out, count);
  }
  batch.changed |= changed;
  return count;
}

// What a pair's contacts add up to: force on body a, its moment about a's centroid (sum r x f),
// the normal parts (sum f_n n), the contact points weighted by normal force (sum f_n r) and that
// weight, the energies, sliding contacts, and the deepest penetration. A contact with area 0 adds
// only the projection energy it had (lawAndSums).
struct PairSums {
  enum Vector { kForce = 0, kMoment = 3, kNormalForce = 6, kWeighted = 9 };
  double value[12] = {};
  double weight = 0, elastic = 0, friction = 0, viscous = 0, sliding = 0, projection = 0, maxDepth = 0;
  Eigen::Vector3d vector(Vector v) const { return {value[v], value[v + 1], value[v + 2]}; }
};

// The contact law (trialSpring and capSpring, as updateSpring; contactForce) over the batch's n
// entries, with the springs, areas and stored energies in `contacts` (the step before's, area -1
// for a new contact; updated in place) and the relative velocity at each node from its lever and
// its side's motion (side s: key bit 31), v = v0_s + w_s x r (SideMotion, in ContactReal), and
// what they add up to, the forces on body a (a node of b, key side 1, has its force on b: -f on
// a), each in the pass that computes it, in SIMD lanes (the sums in ContactReal, the order of the
// additions following the machine's vector width; no force is stored). In whole blocks of
// NodeContacts::kLawBlock entries: the padding entries, all 0 in the batch (key 0, area 0) and in
// the contacts' state arrays (no spring, stored energy or area), add exactly 0 to every sum and
// stay 0.
TESSERA_CPU_VERSIONS
PairSums lawAndSums(const ContactLawConstants<ContactReal>& law, const SideMotion (&sides)[2], PairBatch& b,
                    NodeContacts& contacts, int count) {
  using Real = ContactReal;
  const auto real = [](double v) { return static_cast<Real>(v); };
  const Real ax0 = real(sides[0].v0.x()), ay0 = real(sides[0].v0.y()), az0 = real(sides[0].v0.z());
  const Real ax1 = real(sides[1].v0.x()), ay1 = real(sides[1].v0.y()), az1 = real(sides[1].v0.z());
  const Real sx0 = real(sides[0].spin.x()), sy0 = real(sides[0].spin.y()), sz0 = real(sides[0].spin.z());
  const Real sx1 = real(sides[1].spin.x()), sy1 = real(sides[1].spin.y()), sz1 = real(sides[1].spin.z());
  // Each side's share of the normal energy a change of area changes without work: 0 for blended
  // areas, whose potential's force does that work as the node moves (what the node's turn changes
  // is booked nowhere: the residual's, docs/physics.md); with a per-node stiffness there is no
  // such force (the energy does not scale with the area): 1.
  const bool scalesWithArea = law.perNodeNormal == 0;
  const Real leak0 = sides[0].blendedArea && scalesWithArea ? Real(0) : Real(1), leak1 = sides[1].blendedArea && scalesWithArea ? Real(0) : Real(1);
  b.padFrom(count);
  const int n = static_cast<int>(NodeContacts::padded(static_cast<std::size_t>(count)));
  Real fx = 0, fy = 0, fz = 0, mx = 0, my = 0, mz = 0, nfx = 0, nfy = 0, nfz = 0, wx = 0, wy = 0, wz = 0;
  Real px = 0, py = 0, pz = 0, qx = 0, qy = 0, qz = 0;  // the blended areas' potential force and its moment
  Real weight = 0, elastic = 0, friction = 0, viscous = 0, sliding = 0, projection = 0, deepest = 0;
  const std::uint32_t* __restrict key = b.key.data();
  const Real *__restrict rx = b.rx.data(), *__restrict ry = b.ry.data(), *__restrict rz = b.rz.data(),
             *__restrict nx = b.nx.data(), *__restrict ny = b.ny.data(), *__restrict nz = b.nz.data(),
             *__restrict depth = b.depth.data(), *__restrict area = b.area.data(),
             *__restrict slopeX = b.slopeX.data(), *__restrict slopeY = b.slopeY.data(), *__restrict slopeZ = b.slopeZ.data();
  Real *__restrict ux = contacts.springX.data(), *__restrict uy = contacts.springY.data(),
       *__restrict uz = contacts.springZ.data(), *__restrict stored = contacts.energy.data(),
       *__restrict storedArea = contacts.area.data(), *__restrict normalSpeed = b.normalSpeed.data(),
       *__restrict turned = b.turned.data();
  // The law in three passes, the springs' trial (a division and a square root), their cap
  // (another of each), then the forces and sums: each short enough for the next contacts' work to
  // overlap one's square root and division (in one pass, or two, each contact waited on them).
  // (Every value loaded and one select at a time: a load or a nested select under a condition is
  // control flow, which keeps a loop out of SIMD lanes.)
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const bool one = key[i] >> 31;
    const Real ax = one ? ax1 : ax0, ay = one ? ay1 : ay0, az = one ? az1 : az0;
    const Real sx = one ? sx1 : sx0, sy = one ? sy1 : sy0, sz = one ? sz1 : sz0;
    const Real vx = ax + (sy * rz[i] - sz * ry[i]), vy = ay + (sz * rx[i] - sx * rz[i]), vz = az + (sx * ry[i] - sy * rx[i]);
    const Real vn = vx * nx[i] + vy * ny[i] + vz * nz[i];
    normalSpeed[i] = vn;
    turned[i] = trialSpring(law, nx[i], ny[i], nz[i], vx, vy, vz, vn, ux[i], uy[i], uz[i]);
  }
  // (The sums that need only the cap pass's values are taken there: fewer in the last pass than
  // registers.)
#pragma omp simd reduction(+ : friction, sliding, weight, viscous) reduction(max : deepest)
  for (int i = 0; i < n; ++i) {
    const SpringUpdate<Real> u = capSpring(law, depth[i], area[i], normalSpeed[i], turned[i], ux[i], uy[i], uz[i]);
    friction += u.friction;
    sliding += u.sliding;
    weight += u.normal;
    viscous += u.viscous;
    const Real reached = area[i] > 0 ? depth[i] : Real(0);
    deepest = reached > deepest ? reached : deepest;
  }
#pragma omp simd reduction(+ : fx, fy, fz, mx, my, mz, nfx, nfy, nfz, wx, wy, wz, px, py, pz, qx, qy, qz, elastic, projection)
  for (int i = 0; i < n; ++i) {
    const Real ai = area[i], a0 = storedArea[i], e0 = stored[i];
    const ContactForce<Real> f = contactForce(law, nx[i], ny[i], nz[i], depth[i], ai, normalSpeed[i], ux[i], uy[i], uz[i]);
    stored[i] = f.stored;
    storedArea[i] = ai;
    // Forces on a: +f for a node of a, -f for a node of b (side 1); a contact facing away (area 0)
    // has none.
    const Real side = static_cast<Real>(static_cast<std::int32_t>(key[i] >> 31));
    const Real sign = Real(1) - Real(2) * side;
    const Real gx = sign * f.fx, gy = sign * f.fy, gz = sign * f.fz, gn = sign * f.fn;
    // A blended area's potential adds -1/2 k_n d^2 grad a = -1/2 k_n d (d grad a), summed apart
    // (0 for other areas: their sums keep their bits).
    const Real pull = sign * Real(-0.5) * law.perAreaNormal * depth[i];
    const Real ex = pull * slopeX[i], ey = pull * slopeY[i], ez = pull * slopeZ[i];
    px += ex;
    py += ey;
    pz += ez;
    qx += ry[i] * ez - rz[i] * ey;
    qy += rz[i] * ex - rx[i] * ez;
    qz += rx[i] * ey - ry[i] * ex;
    fx += gx;
    fy += gy;
    fz += gz;
    mx += ry[i] * gz - rz[i] * gy;
    my += rz[i] * gx - rx[i] * gz;
    mz += rx[i] * gy - ry[i] * gx;
    nfx += gn * nx[i];
    nfy += gn * ny[i];
    nfz += gn * nz[i];
    wx += f.fn * rx[i];
    wy += f.fn * ry[i];
    wz += f.fn * rz[i];
    elastic += f.stored;
    // Stored energy is proportional to the area (with stiffnesses per area; per node it is not):
    // what the change of area alone removed, the energy per area times the area lost (a contact
    // coming back from a cut, area 0, brings all of its energy back; a cut takes all of it). A
    // blended area's normal energy changes by its potential's work: only the spring's is booked
    // (and a cut's, which a blended area reaches near 0).
    const Real u2 = ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i];
    const Real leak = leak0 + (leak1 - leak0) * side;  // arithmetic, not a select: the loop stays in SIMD lanes
    const Real perArea = leak * Real(0.5) * law.perAreaNormal * depth[i] * depth[i] + Real(0.5) * law.perAreaTangent * u2;
    Real removed = a0 >= 0 ? perArea * (a0 - ai) : Real(0);  // kept (a new contact: -1)
    removed = a0 == 0 ? leak * -f.stored + (Real(1) - leak) * removed : removed;  // back from a cut
    removed = ai > 0 ? removed : e0;                          // cut now
    projection += removed;
  }
  PairSums sums;
  const Real value[12] = {fx + px, fy + py, fz + pz, mx + qx, my + qy, mz + qz, nfx, nfy, nfz, wx, wy, wz};
  std::copy(value, value + 12, sums.value);
  sums.weight = weight;
  sums.elastic = elastic;
  sums.friction = friction;
  sums.viscous = viscous;
  sums.sliding = sliding;
  sums.projection = projection;
  sums.maxDepth = deepest;
  return sums;
}

// Per-thread scratch (kept from pair to pair and step to step: no allocation once grown).
struct Scratch {
  PairBatch batch;
  // The candidates of one side against a non-convex other side: their level set (or the grid's
  // value), the indices of those near the surface, their positions in the other side's frame, and
  // there the grid's gradient direction (then the level set's unit normal).
  std::vector<double> phi, ox, oy, oz, gx, gy, gz;
  std::vector<int> inside;
  void reserve(int n) {
    if (static_cast<int>(phi.size()) >= n) return;
    for (auto* v : {&phi, &ox, &oy, &oz, &gx, &gy, &gz}) v->resize(static_cast<std::size_t>(n));
    inside.resize(static_cast<std::size_t>(n));
  }
};
thread_local Scratch threadScratch;

// Collects a pair's node contacts side by side, then runs the law over all of them and sums
// their forces: the force on body a with its torque about a's centroid; b's follow (equal and
// opposite force; torque moved by the short lever between the two centroids, no cancellation
// against moments about a far origin).
struct Accumulator {
  const ContactScene& scene;
  PairContacts& pair;
  Eigen::Vector3d centreA;  // m, body a's centroid
  double kn, kt;            // N/m^3, this pair's stiffnesses
  PairBatch& batch;
  SideMotion sides[2]{};  // each side's motion (an obstacle pair has side 0 only: side 1 stays 0)
  std::uint32_t side = 0;  // the side being collected

  // Starts side s: the nodes of the body moving as `node` in the other side, moving as `other`.
  const SideMotion& beginSide(std::uint32_t s, const Motion& node, const Motion& other) {
    side = s;
    SideMotion& m = sides[s];
    m.shift = node.position - centreA;
    m.spin = node.angularVelocity - other.angularVelocity;
    m.v0 = node.velocity - other.velocity + other.angularVelocity.cross(other.position - centreA) -
           node.angularVelocity.cross(m.shift);
    return m;
  }
  // One node of the side's body at r = x - c_M (world), inside the other side by depth along
  // `normal` (world, out of the other side), with its share of its node's area and the projection
  // -n_i . n of its outward normal n_i on the contact normal: its effective area is area x
  // projection, the node's area projected on the contact plane (docs/physics.md), 0 when it
  // faces away.
  void add(std::uint32_t key, const Eigen::Vector3d& r, double projection, double area, const Eigen::Vector3d& normal,
           double depth) {
    const BatchSlice out(batch, batch.append());
    out.key[0] = key;
    const auto real = [](double v) { return static_cast<ContactReal>(v); };
    const Eigen::Vector3d lever = r + sides[side].shift;
    out.rx[0] = real(lever.x());
    out.ry[0] = real(lever.y());
    out.rz[0] = real(lever.z());
    out.nx[0] = real(normal.x());
    out.ny[0] = real(normal.y());
    out.nz[0] = real(normal.z());
    out.depth[0] = real(depth);
    out.area[0] = real(facingArea(area, projection));
    out.slopeX[0] = out.slopeY[0] = out.slopeZ[0] = 0;
  }

  // The pair's contacts as they were before this step, for the batch's keys: each one's spring,
  // area and stored energy from the previous evaluation's contacts (pair.previous; new contacts:
  // no spring, area -1, no energy); the law updates them in place. Most steps a pair's node
  // contacts are the same as before (known from the listing's blocks, PairBatch::changed, or
  // else from the keys): then the previous arrays become the contacts' as they are. Otherwise the
  // two key-sorted lists are merged: `before` stays on an entry (the last at most), so that every
  // load is made and `found` only selects, no branch but the merge's own.
  void takeHistory(int n) {
    const NodeContacts& previous = pair.previous;
    const std::uint32_t* key = batch.key.data();
    const bool sameSize = previous.size() == static_cast<std::size_t>(n);
    const bool same = batch.changed == 0 ? sameSize : batch.changed < 0 && sameSize && std::equal(key, key + n, previous.key.data());
    assert(!same || std::equal(key, key + n, previous.key.data()));
    if (same) {
      std::swap(pair.contacts, pair.previous);
      return;
    }
    NodeContacts& contacts = pair.contacts;
    contacts.resize(static_cast<std::size_t>(n));
    std::copy_n(key, n, contacts.key.data());
    if (previous.empty()) {
      std::fill_n(contacts.springX.data(), n, ContactReal(0));
      std::fill_n(contacts.springY.data(), n, ContactReal(0));
      std::fill_n(contacts.springZ.data(), n, ContactReal(0));
      std::fill_n(contacts.area.data(), n, ContactReal(-1));
      std::fill_n(contacts.energy.data(), n, ContactReal(0));
      return;
    }
    const std::size_t last = previous.size() - 1;
    const std::uint32_t* __restrict keyBefore = previous.key.data();
    const ContactReal *__restrict sx = previous.springX.data(), *__restrict sy = previous.springY.data(),
                 *__restrict sz = previous.springZ.data(), *__restrict areaBefore = previous.area.data(),
                 *__restrict energyBefore = previous.energy.data();
    std::size_t before = 0;
    for (int i = 0; i < n; ++i) {
      while (before < last && keyBefore[before] < key[i]) ++before;
      const bool found = keyBefore[before] == key[i];
      contacts.springX[i] = found ? sx[before] : ContactReal(0);
      contacts.springY[i] = found ? sy[before] : ContactReal(0);
      contacts.springZ[i] = found ? sz[before] : ContactReal(0);
      contacts.area[i] = found ? areaBefore[before] : ContactReal(-1);
      contacts.energy[i] = found ? energyBefore[before] : ContactReal(0);
    }
  }

  // The law over the pair's contacts; their springs and forces stored in the pair.
  void finish() {
    const int n = batch.count;
    takeHistory(n);
    NodeContacts& contacts = pair.contacts;
    const auto law = ContactLawConstants<ContactReal>::of(scene.parameters, kn, kt, scene.dt);
    const PairSums sums = lawAndSums(law, sides, batch, contacts, n);

    pair.tally.projection = sums.projection;
    pair.tally.elastic = sums.elastic;
    pair.tally.friction = sums.friction;
    pair.tally.viscous = sums.viscous;
    pair.tally.sliding = static_cast<int>(sums.sliding);
    pair.maxDepth = sums.maxDepth;
    pair.forceA = sums.vector(PairSums::kForce);
    pair.torqueA = sums.vector(PairSums::kMoment);
    pair.normalForceA = sums.vector(PairSums::kNormalForce);
    pair.forcePoint = sums.weight > 0 ? Eigen::Vector3d(centreA + sums.vector(PairSums::kWeighted) / sums.weight)
                                      : Eigen::Vector3d::Zero();
    // Newton's third law: on b, -F_A at the same points: tau_B = -(tau_A + (c_A - c_B) x F_A).
    pair.forceB = -pair.forceA;
    if (pair.b >= 0) pair.torqueB = -(pair.torqueA + (centreA - scene.bodies->position[pair.b]).cross(pair.forceA));
    batch.count = 0;
    batch.changed = -1;
  }
};

// Visits the nodes of one side (key = side << 31 | rank) that can touch: the pair's candidates
// of that side or, when they are being rebuilt, every node in `region`, keeping as candidates
// those with phi below the band. `test(key)` returns the node's phi.
template <class Test>
void visitSide(const NodeBins& nodes, const Eigen::AlignedBox3d& region, std::uint32_t side, bool rebuild,
               double band, PairContacts& pair, Test&& test) {
  if (rebuild) {
    pair.candidates.beginSide(side);
    nodes.forEachNodeIn(region, [&](int rank) {
      const std::uint32_t key = side << 31 | static_cast<std::uint32_t>(rank);
      if (test(key) < band) pair.candidates.add(key, nodes, rank);
    });
    pair.candidates.endSide(side);
    return;
  }
  const SideCandidates c = candidatesOf(pair, side);
  for (int i = 0; i < c.n; ++i) test(c.key[i]);
}

// The contacts of one side's candidates in a convex other side (convexContacts), added to the batch.
void convexSideContacts(PairContacts& pair, std::uint32_t side, const PlanesInFrame& planes, const Eigen::Matrix3d& RM,
                        const SideMotion& motion, double share, PairBatch& batch) {
  const SideCandidates c = candidatesOf(pair, side);
  pair.evaluations += c.n;
  batch.reserve(batch.count + c.n + kLanes);
  batch.count += convexContacts(batch.count, c, planes, motion, RM, share, batch);
}

// The contacts of one side's candidates in a non-convex other side O (its exact mesh or grid level
// set): every candidate's position in O's frame and the grid's value and gradient there (SIMD, no
// branches), then the level set for those the grid's value does not settle
// (ShapeModel::gridValueBound): from that gradient on the grid path, from the exact mesh where O
// has one; and their contacts. `toO`, `shift`: O's frame from M's; `offset` = c_O - c_M.
void levelSetSideContacts(PairContacts& pair, std::uint32_t side, const ShapeModel& so, const Eigen::Matrix3d& toO,
                          const Eigen::Vector3d& shift, const Eigen::Matrix3d& RM, const Eigen::Matrix3d& RO,
                          const Eigen::Vector3d& offset, const SideMotion& motion, double share, Scratch& scratch) {
  const SideCandidates c = candidatesOf(pair, side);
  const int n = c.n;
  scratch.reserve(n + kLanes);
  double *ox = scratch.ox.data(), *oy = scratch.oy.data(), *oz = scratch.oz.data();
  double *phi = scratch.phi.data(), *gx = scratch.gx.data(), *gy = scratch.gy.data(), *gz = scratch.gz.data();
  transformPoints(n, toO, shift, c.x, c.y, c.z, ox, oy, oz);
  if (so.sdf.values.size() < static_cast<std::size_t>(std::numeric_limits<int>::max()))
    gridSamples(so.sdf, n, ox, oy, oz, phi, gx, gy, gz);
  else  // a grid too large for int indices
    for (int i = 0; i < n; ++i) {
      const SdfSample s = so.sdf.sample(Eigen::Vector3d(ox[i], oy[i], oz[i]));
      phi[i] = s.phi;
      gx[i] = s.gradient.x();
      gy[i] = s.gradient.y();
      gz[i] = s.gradient.z();
    }
  pair.evaluations += n;
  int* inside = scratch.inside.data();
  if (so.exactMesh.empty()) {
    gridLevelSets(n, phi, gx, gy, gz);
  } else {
    // The exact level set where the grid's value does not settle it; the grid's value elsewhere
    // (outside: no normal needed).
    const double bound = so.gridValueBound();
    int near = 0;
    for (int i = 0; i < n; ++i) {
      inside[near] = i;
      near += phi[i] <= bound;
    }
    // Each candidate's NearestFace, kept from its last exact evaluation (the same bits as the
    // search); new candidates (side 1's, appended after side 0's were evaluated) start empty.
    CandidateNodes& all = pair.candidates;
    if (all.nearestFace.size() != all.size()) all.nearestFace.resize(all.size());
    MeshSdf::NearestFace* kept = all.nearestFace.data() + (c.key - all.key.data());
    for (int k = 0; k < near; ++k) {
      const int i = inside[k];
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      phi[i] = so.meshLevelSet(Eigen::Vector3d(ox[i], oy[i], oz[i]), phi[i], normal, kept + i);
      gx[i] = normal.x();
      gy[i] = normal.y();
      gz[i] = normal.z();
    }
  }
  std::fill_n(phi + n, kLanes, NAN);  // the last block's padding: never inside
  PairBatch& batch = scratch.batch;
  batch.reserve(batch.count + n + kLanes);
  batch.count += levelSetContacts(batch.count, c, motion, ox, oy, oz, phi, gx, gy, gz, RO, RM, offset, share, batch);
}

// The other side's world pose: body b's; an obstacle's centre or point, unturned.
std::pair<Eigen::Vector3d, Eigen::Quaterniond> otherPose(const ContactScene& scene, const PairContacts& pair) {
  switch (pair.kind) {
    case PairKind::Bodies: return {scene.bodies->position[pair.b], scene.bodies->orientation[pair.b]};
    case PairKind::Sphere: return {(*scene.spheres)[-1 - pair.b].center, Eigen::Quaterniond::Identity()};
    case PairKind::Plane: break;
  }
  return {(*scene.planes)[-1 - pair.b - static_cast<int>(scene.spheres->size())].point, Eigen::Quaterniond::Identity()};
}

// m, the two sides' summed Travel (a plane does not move).
double sidesTravel(const Travel& t, const PairContacts& pair) {
  switch (pair.kind) {
    case PairKind::Bodies: return t.body[pair.a] + t.body[pair.b];
    case PairKind::Sphere: return t.body[pair.a] + t.sphere[-1 - pair.b];
    case PairKind::Plane: break;
  }
  return t.body[pair.a];
}

// Clears the pair's last evaluation (its contacts become the history) and says whether its
// candidate nodes are to be rebuilt: when they are not valid, or the sides have moved too far
// relative to each other since they were built (ContactScene::candidateBand).
bool beginEvaluation(const ContactScene& scene, PairContacts& pair) {
  std::swap(pair.contacts, pair.previous);
  pair.forceA = pair.torqueA = pair.forceB = pair.torqueB = pair.normalForceA = pair.forcePoint = Eigen::Vector3d::Zero();
  pair.tally = ContactTally{};
  pair.maxDepth = 0.0;
  pair.evaluations = 0;
  const double travel = scene.travel != nullptr ? sidesTravel(*scene.travel, pair) : 0.0;
  const bool mayHaveMoved = scene.travel == nullptr || kSqrt3 * (pair.checkedMotion + (travel - pair.checkedTravel)) >= scene.candidateBand;
  bool rebuild = !pair.candidatesValid;
  // The exact motion only when the bound from the travel since it was last computed can reach the
  // threshold: the same decisions as computing it every step.
  if (!rebuild && mayHaveMoved) {
    pair.checkedMotion = candidateMotion(scene, pair);
    pair.checkedTravel = travel;
    rebuild = kSqrt3 * pair.checkedMotion >= scene.candidateBand;
  }
  if (rebuild) {
    pair.checkedMotion = 0.0;
    pair.checkedTravel = travel;
    pair.candidates.clear();
    pair.builtPositionA = scene.bodies->position[pair.a];
    pair.builtOrientationA = scene.bodies->orientation[pair.a];
    std::tie(pair.builtPositionB, pair.builtOrientationB) = otherPose(scene, pair);
  }
  pair.candidatesValid = true;
  return rebuild;
}

// A body's nodes (full area) against an analytic obstacle moving as `other`; phiAndNormal(x, n)
// gives phi at a world point and, inside, the obstacle's outward normal.
template <class PhiAndNormal>
void visitObstacle(const ContactScene& scene, PairContacts& pair, Accumulator& acc, bool rebuild,
                   const Eigen::AlignedBox3d& region, const Motion& other, PhiAndNormal&& phiAndNormal) {
  const RigidBodies& bodies = *scene.bodies;
  const int m = pair.a;
  const ShapeModel& sm = (*scene.shapes)[bodies.shape[m]];
  const Eigen::Matrix3d& RM = scene.kinematics->rotation[m];
  const Motion node = motionOf(scene, m);
  acc.batch.changed = -1;  // listed node by node: the history by its keys
  acc.beginSide(0, node, other);
  visitSide(sm.nodes, region, 0, rebuild, scene.candidateBand, pair, [&](std::uint32_t key) {
    ++pair.evaluations;
    const Eigen::Vector3d r = RM * sm.nodes.position[key];
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    const double phi = phiAndNormal(r + node.position, normal);
    if (phi < 0) acc.add(key, r, -(RM * sm.nodes.normal[key]).dot(normal), sm.nodes.area[key], normal, -phi);
    return phi;
  });
  acc.finish();
}

}  // namespace

double candidateMotion(const ContactScene& scene, const PairContacts& pair) {
  const RigidBodies& bodies = *scene.bodies;
  const auto& shapes = *scene.shapes;
  const auto moved = [](const Eigen::Vector3d& p, const Eigen::Quaterniond& q, const Eigen::Vector3d& p0,
                        const Eigen::Quaterniond& q0, double radius) { return (p - p0).norm() + turnChord(q, q0) * radius; };
  const auto [position, orientation] = otherPose(scene, pair);
  return moved(bodies.position[pair.a], bodies.orientation[pair.a], pair.builtPositionA, pair.builtOrientationA,
               shapes[bodies.shape[pair.a]].radius) +
         moved(position, orientation, pair.builtPositionB, pair.builtOrientationB,
               pair.kind == PairKind::Bodies ? shapes[bodies.shape[pair.b]].radius : 0.0);
}

void evaluatePair(const ContactScene& scene, PairContacts& pair) {
  switch (pair.kind) {
    case PairKind::Bodies: return evaluateBodyPair(scene, pair);
    case PairKind::Sphere: return evaluateSpherePair(scene, pair);
    case PairKind::Plane: return evaluatePlanePair(scene, pair);
  }
}

void evaluateBodyPair(const ContactScene& scene, PairContacts& pair) {
  const bool rebuild = beginEvaluation(scene, pair);
  if (!rebuild && pair.candidates.nodes() == 0) {  // no node within the band: no contact until rebuilt
    pair.contacts.clear();
    return;
  }
  Scratch& scratch = threadScratch;
  const auto [kn, kt] = pairStiffness(scene.parameters, scene.kn, scene.kt, pair.stiffnessScale, 1.0);
  Accumulator acc{scene, pair, scene.bodies->position[pair.a], kn, kt, scratch.batch};
  scratch.batch.changed = 0;  // listed by blocks (both sides)
  const RigidBodies& bodies = *scene.bodies;
  const auto& shapes = *scene.shapes;
  for (std::uint32_t side = 0; side < 2; ++side) {
    const int m = side == 0 ? pair.a : pair.b, o = side == 0 ? pair.b : pair.a;
    const ShapeModel& sm = shapes[bodies.shape[m]];
    const ShapeModel& so = shapes[bodies.shape[o]];
    const double share = scene.parameters.sideAreaShare(static_cast<int>(side), shapes[bodies.shape[pair.a]].volume,
                                                        shapes[bodies.shape[pair.b]].volume);
    if (share == 0) continue;  // one-way: the larger body's nodes are not tested
    const Eigen::Matrix3d &RM = scene.kinematics->rotation[m], &RO = scene.kinematics->rotation[o];
    const Eigen::Matrix3d toO = RO.transpose() * RM;  // M body -> O body
    const Eigen::Vector3d shift = RO.transpose() * (bodies.position[m] - bodies.position[o]);
    const Motion node = motionOf(scene, m), other = motionOf(scene, o);
    // Only nodes inside the other body's box (and band) can be inside the other body.
    Eigen::AlignedBox3d region;
    if (rebuild) {
      region = regionInFrame(so.box, bodies.orientation[o], other.position, bodies.orientation[m], node.position);
      region.min().array() -= scene.candidateBand;
      region.max().array() += scene.candidateBand;
    }
    const SideMotion& motion = acc.beginSide(side, node, other);
    const bool blend = scene.parameters.area == ContactArea::Blended;
    if (!so.planes.empty()) {
      // A convex other side: its planes moved into M's frame once, n' = toO^T n, d' = d - n . shift,
      // so that a candidate is tested as it is: phi = max_f (n'_f . p - d'_f).
      // The candidates first, if they are being rebuilt, and the planes near them; then every
      // candidate's phi at once (SIMD), the ones inside listed without branches, and their
      // contacts: one path for every step, so that a run resumed from a checkpoint (which rebuilds
      // them) gives the same bits.
      if (rebuild) {
        const PlanesInFrame all(so.planes, toO, shift);
        visitSide(sm.nodes, region, side, rebuild, scene.candidateBand, pair, [&](std::uint32_t key) {
          ++pair.evaluations;
          int best;
          return all.phi(sm.nodes.position[key & kRankMask], best);
        });
        pair.planesKept[side] = planesNear(candidatesOf(pair, side), all, scene.candidateBand, blend ? kAreaBlendWidth : 0.0);
      }
      acc.sides[side].blendedArea = blend;
      const PlanesInFrame planes(so.planes, toO, shift, pair.planesKept[side]);
      convexSideContacts(pair, side, planes, RM, motion, share, scratch.batch);
    } else {
      // As for a convex side: the candidates first (if rebuilt), then the level set of all of them.
      if (rebuild)
        visitSide(sm.nodes, region, side, rebuild, scene.candidateBand, pair, [&](std::uint32_t key) {
          ++pair.evaluations;
          return so.candidateValue(toO * sm.nodes.position[key & kRankMask] + shift);
        });
      levelSetSideContacts(pair, side, so, toO, shift, RM, RO, other.position - node.position, motion, share, scratch);
    }
  }
  acc.finish();
}

void evaluateSpherePair(const ContactScene& scene, PairContacts& pair) {
  const bool rebuild = beginEvaluation(scene, pair);
  const SphereObstacle& sphere = (*scene.spheres)[-1 - pair.b];
  const auto [kn, kt] = pairStiffness(scene.parameters, scene.kn, scene.kt, pair.stiffnessScale, sphere.stiffnessFactor);
  Accumulator acc{scene, pair, scene.bodies->position[pair.a], kn, kt, threadScratch.batch};
  const Eigen::Vector3d& position = scene.bodies->position[pair.a];
  const Eigen::Vector3d centre = scene.bodies->orientation[pair.a].conjugate() * (sphere.center - position);
  const double reach = sphere.radius + scene.candidateBand;
  visitObstacle(scene, pair, acc, rebuild, Eigen::AlignedBox3d(centre.array() - reach, centre.array() + reach),
                Motion{sphere.center, sphere.velocity, Eigen::Vector3d::Zero()},
                [&](const Eigen::Vector3d& x, Eigen::Vector3d& normal) {
                  const double phi = sphere.phi(x);
                  if (phi < 0) normal = sphere.normal(x);
                  return phi;
                });
}

void evaluatePlanePair(const ContactScene& scene, PairContacts& pair) {
  const bool rebuild = beginEvaluation(scene, pair);
  const PlaneObstacle& plane = (*scene.planes)[-1 - pair.b - static_cast<int>(scene.spheres->size())];
  const auto [kn, kt] = pairStiffness(scene.parameters, scene.kn, scene.kt, pair.stiffnessScale, 1.0);
  Accumulator acc{scene, pair, scene.bodies->position[pair.a], kn, kt, threadScratch.batch};
  const ShapeModel& sm = (*scene.shapes)[scene.bodies->shape[pair.a]];
  visitObstacle(scene, pair, acc, rebuild, sm.nodes.box, Motion{plane.point, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()},
                [&](const Eigen::Vector3d& x, Eigen::Vector3d& normal) {
                  normal = plane.normal;
                  return plane.phi(x);
                });
}

}  // namespace tessera
