#include "solver/implicit_contacts.h"

#include "solver/blended_area.h"
#include "solver/cpu_versions.h"
#include "solver/node_contact_law.h"
#include "solver/planes_in_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

}  // namespace

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

namespace {

// One side of a pair: the node's body M and the other side O, at the trial configuration and at
// the increment's start. A node at body-frame position x_b is at p = R_M x_b + c_M (world) and at
// y = R_O^T (p - c_O) in O's frame; its displacement relative to O over the increment is
// rel = R_O (y - y0): the node's motion less that of O's material point it was at.
// (rel = R_O (toO x + shift - toO0 x - shift0) = relMatrix x + relShift.)
struct SidePoses {
  Eigen::Matrix3d RM, RO, toO, relMatrix;
  Eigen::Vector3d cM, shift, relShift;
};

SidePoses posesOf(const Eigen::Matrix3d& RM, const Eigen::Vector3d& cM, const Eigen::Matrix3d& RO, const Eigen::Vector3d& cO,
                  const Eigen::Matrix3d& RM0, const Eigen::Vector3d& cM0, const Eigen::Matrix3d& RO0, const Eigen::Vector3d& cO0) {
  const Eigen::Matrix3d toO = RO.transpose() * RM, toO0 = RO0.transpose() * RM0;
  const Eigen::Vector3d shift = RO.transpose() * (cM - cO), shift0 = RO0.transpose() * (cM0 - cO0);
  return {RM, RO, toO, RO * (toO - toO0), cM, shift, RO * (shift - shift0)};
}

// The region of M's frame that O's box (in O's frame) covers.
Eigen::AlignedBox3d boxInNodeFrame(const Eigen::AlignedBox3d& otherBox, const SidePoses& s) {
  Eigen::AlignedBox3d region;
  for (int corner = 0; corner < 8; ++corner)
    region.extend(s.toO.transpose() * (otherBox.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)) - s.shift));
  return region;
}

// m += c v v^T in m's lower triangle (inline: Eigen's rankUpdate is a call per contact).
template <int N>
inline void addOuterLower(Eigen::Matrix<double, N, N>& m, const Eigen::Matrix<double, N, 1>& v, double c) {
  for (int j = 0; j < N; ++j) {
    const double cv = c * v[j];
    for (int i = j; i < N; ++i) m(i, j) += v[i] * cv;
  }
}

// The law's constants for a pair (its stiffnesses: pairStiffness) over a rate step dt.
ContactLawConstants<double> lawOf(const ImplicitScene& scene, const PairContacts& pair, double factor, double dt) {
  const auto [kn, kt] = pairStiffness(scene.parameters, scene.kn, scene.kt, pair.stiffnessScale, factor);
  return ContactLawConstants<double>::of(scene.parameters, kn, kt, dt);
}

// The law over a pair's contacts as they are found, and what they add up to.
class Accumulator {
public:
  Accumulator(const ImplicitScene& scene, const PairContacts& pair, const NodeContacts& committed, double stiffnessFactor,
              ImplicitPairResult& out)
      : committed_(committed), out_(out), centreA_(scene.bodies->position[pair.a]), increment_(scene.increment),
        trialLaw_(lawOf(scene, pair, stiffnessFactor, 1.0)),
        rateLaw_(lawOf(scene, pair, stiffnessFactor, scene.increment)) {
    std::vector<NodeContact> kept = std::move(out_.contacts);  // its capacity, not its values
    out_ = ImplicitPairResult{};
    out_.contacts = std::move(kept);
    out_.contacts.clear();
  }

  // A node inside the other side: its key, world position p, the other side's outward normal n
  // (world), its depth, effective area a (0: facing away), displacement relative to the other
  // side over the increment, sign +1 for a node of a, -1 for a node of b, and the curvature of
  // the other side's level set there (1/m: a sphere's 1 / |x - c|; 0 for planes) with the
  // gradient of the effective area it gives, d a / d(rel) (m; 0 for planes), and the area's
  // change with the node's body turning against the other side, d a / d(theta_M - theta_O) (m^2).
  // blended: the area is blended (blended_area.h) with the gradient areaGradient, and the contact
  // carries its potential's force -1/2 k_n d^2 grad a.
  void add(std::uint32_t key, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double depth, double area,
           const Eigen::Vector3d& rel, double sign, double curvature, const Eigen::Vector3d& areaGradient,
           const Eigen::Vector3d& areaTurn, bool blended) {
    // The committed spring, area and energy of this node contact (none: a new contact, area -1).
    Eigen::Vector3d spring = Eigen::Vector3d::Zero();
    double areaBefore = -1.0, energyBefore = 0.0;
    // Keys come in increasing order (side 0's nodes by rank, then side 1's), as the committed ones.
    while (next_ < committed_.size() && committed_.key[next_] < key) ++next_;
    if (next_ < committed_.size() && committed_.key[next_] == key) {
      const NodeContact c = committed_[next_];
      spring = c.spring;
      areaBefore = c.area;
      energyBefore = c.energy;
    }
    // The law of the explicit step with v dt = rel: the spring turned onto the tangent plane plus
    // the tangential part of rel, capped at mu f_n; the normal viscosity at the normal speed.
    const double vn = rel.dot(n), rate = increment_ > 0 ? vn / increment_ : 0.0;
    double ux = spring.x(), uy = spring.y(), uz = spring.z();
    const double turnedDotTrial = trialSpring(trialLaw_, n.x(), n.y(), n.z(), rel.x(), rel.y(), rel.z(), vn, ux, uy, uz);
    const Eigen::Vector3d trial(ux, uy, uz);
    const SpringUpdate<double> update = capSpring(rateLaw_, depth, area, rate, turnedDotTrial, ux, uy, uz);
    const ContactForce<double> f = contactForce(rateLaw_, n.x(), n.y(), n.z(), depth, area, rate, ux, uy, uz);
    const double pull = blended ? -0.5 * rateLaw_.perAreaNormal * depth * depth : 0.0;
    const Eigen::Vector3d force = Eigen::Vector3d(f.fx, f.fy, f.fz) + pull * areaGradient;

    // K = -df / d(rel) (docs/physics.md, "Implicit method"):
    //   normal     (k_n a + eta_n a / dt) n n^T                       while f_n > 0
    //   sticking   k_t a (I - n n^T)
    //   sliding    mu f_n / |s| (I - s^ s^T)(I - n n^T) - mu (k_n a + eta_n a / dt) s^ n^T
    // (s: the trial spring; sliding, f_t = -mu f_n s^). The normal turning with a plane of the
    // other side as that side turns is left out: f / (k a r) = d / r of the terms kept (the lever
    // turning with the body is pairTangent's geometric part). On a curved other side (the indenter) the
    // normal turns as the node slides, dn = kappa (I - n n^T) d(rel), which softens the contact
    // tangentially by -f_n kappa (I - n n^T): d / R of k_n a, several per cent under the
    // indenter, and kept.
    // G^T K G is summed without forming it: with t^ = n x s^ (s^ lies in the tangent plane), the
    // sliding K is (k_N + f_n kappa) n n^T + mu f_n / |s| t^ t^T - f_n kappa I - mu k_N s^ n^T and
    // the sticking K is (k_N - k_t a + f_n kappa) n n^T + (k_t a - f_n kappa) I (k_N = k_n a +
    // eta_n a / dt): rank-one terms G^T e e'^T G = w_e w_e'^T with w_e = G^T e = [e; r x e], and an
    // isotropic part whose sum over the contacts is taken from the moments of its coefficient over
    // the levers (finish()).
    const Eigen::Vector3d r = p - centreA_;
    if (f.fn > 0) {
      const NormalForce<double> nf = normalForce(rateLaw_, depth, area, rate);
      const double kNormal = nf.kna + (increment_ > 0 ? rateLaw_.viscosity * area / increment_ : 0.0);
      const double softening = f.fn * curvature;
      Eigen::Matrix<double, 6, 1> wn;
      wn << n, r.cross(n);
      const double length = trial.norm();
      // On a curved other side the tangential part of rel, (I - n n^T) rel, turns with n too:
      // d s / d rel = (1 - kappa n . rel) (I - n n^T) - kappa n rel_t^T.
      const double along = 1 - curvature * n.dot(rel);
      double isotropic, turning;
      if (update.sliding > 0 && length > 0) {
        const Eigen::Vector3d s = trial / length, t = n.cross(s);
        Eigen::Matrix<double, 6, 1> wt, ws;
        wt << t, r.cross(t);
        ws << s, r.cross(s);
        addOuterLower(symmetric_, wn, kNormal + softening);
        addOuterLower(symmetric_, wt, along * rateLaw_.friction * f.fn / length);
        out_.stiffness.noalias() -= (rateLaw_.friction * kNormal) * ws * wn.transpose();
        isotropic = -softening;
        turning = rateLaw_.friction * f.fn / length;
      } else {
        addOuterLower(symmetric_, wn, kNormal - along * nf.kta + softening);
        isotropic = along * nf.kta - softening;
        turning = nf.kta;
      }
      if (curvature > 0) {
        const Eigen::Vector3d relT = rel - n * n.dot(rel);
        Eigen::Matrix<double, 6, 1> wr;
        wr << relT, r.cross(relT);
        out_.stiffness.noalias() -= (turning * curvature) * wn * wr.transpose();
      }
      // The effective area a = A max(0, -n_i . n) changes as n turns (on a curved other side)
      // and as the node's body turns against the other side:
      // K += -(d f / d a) (d a / d (rel, theta))^T, d f / d a = k_n d n - k_t u (sliding: k_n d (n - mu s^)).
      if (areaGradient.squaredNorm() > 0 || areaTurn.squaredNorm() > 0) {
        const Eigen::Vector3d u(ux, uy, uz);
        const Eigen::Vector3d perArea = rateLaw_.perAreaNormal * depth * n -
                                        (update.sliding > 0 && length > 0 ? Eigen::Vector3d(rateLaw_.friction * rateLaw_.perAreaNormal * depth * trial / length)
                                                                          : Eigen::Vector3d(rateLaw_.perAreaTangent * u));
        Eigen::Matrix<double, 6, 1> wf, wa;
        wf << perArea, r.cross(perArea);
        wa << areaGradient, r.cross(areaGradient) + areaTurn;
        out_.stiffness.noalias() -= wf * wa.transpose();
        // The potential's force -1/2 k_n d^2 grad a changes with the depth: K += -k_n d grad a n^T.
        // Its change with grad a, 1/2 k_n d^2 times the area's second derivatives, is left out: of
        // the order k_n A / c^2 inside the blend's wedge (as large as the terms kept there, for the
        // few nodes within c d of a second plane), so Newton converges more slowly where nodes
        // cross an edge's bisector, not to another answer.
        if (blended) {
          Eigen::Matrix<double, 6, 1> wg;
          wg << areaGradient, r.cross(areaGradient);
          out_.stiffness.noalias() -= (rateLaw_.perAreaNormal * depth) * wg * wn.transpose();
        }
      }
      isotropic_ += isotropic;
      isotropicLever_ += isotropic * r;
      addOuterLower(isotropicSecond_, r, isotropic);
    }
    const Eigen::Vector3d g = sign * force;
    out_.force.head<3>() += g;
    out_.force.tail<3>() += r.cross(g);
    const int side = sign > 0 ? 0 : 1;
    out_.sideForce[side] += g;
    leverTimesForce_[side].noalias() += r * g.transpose();
    out_.normalForceA += sign * f.fn * n;
    forcePointSum_ += f.fn * r;
    weight_ += f.fn;
    out_.forceScale += (1 + rateLaw_.friction) * f.fn;  // at least |f|, without a square root
    out_.maxDepth = std::max(out_.maxDepth, depth);
    out_.tally.elastic += f.stored;
    out_.tally.friction += update.friction;
    out_.tally.viscous += update.viscous;
    out_.tally.sliding += static_cast<int>(update.sliding);
    // Stored energy proportional to the area: what the change of area alone removed
    // (ContactTally::projection), the area's change times the energy per area, which the explicit
    // step takes at the step's end and an increment as the mean of its start and end (the
    // trapezoidal rule: an increment's change is not small).
    // A blended area's normal energy changes, as the node moves, by its potential's work: only the
    // spring's is booked (with a per-node stiffness the normal energy does not scale with the area
    // and has no such force: booked whole). What its change with the node's turn adds is booked
    // nowhere (the residual's: docs/physics.md).
    const bool potential = blended && rateLaw_.perNodeNormal == 0;
    const double leak = potential ? 0.0 : 1.0;
    const double perArea = leak * 0.5 * rateLaw_.perAreaNormal * depth * depth + 0.5 * rateLaw_.perAreaTangent * (ux * ux + uy * uy + uz * uz);
    const double perAreaBefore = !(areaBefore > 0) || rateLaw_.perNodeNormal != 0 ? perArea
                                 : potential ? 0.5 * rateLaw_.perAreaTangent * spring.squaredNorm()
                                           : energyBefore / areaBefore;
    double removed = areaBefore >= 0 ? 0.5 * (perAreaBefore + perArea) * (areaBefore - area) : 0.0;
    if (areaBefore == 0 && !potential) removed = -f.stored;
    if (!(area > 0)) removed = energyBefore;
    out_.tally.projection += removed;
    out_.contacts.push_back({key, Eigen::Vector3d(ux, uy, uz), f.stored, area});
  }

  void finish() {
    out_.forcePoint = weight_ > 0 ? Eigen::Vector3d(centreA_ + forcePointSum_ / weight_) : Eigen::Vector3d::Zero();
    // The symmetric rank-one updates filled a lower triangle; the isotropic part
    //   sum k G^T G = [[sum k I, -[sum k r]x], [[sum k r]x, sum k (|r|^2 I - r r^T)]].
    const Eigen::Matrix3d second = isotropicSecond_.selfadjointView<Eigen::Lower>();
    Eigen::Matrix<double, 6, 6> iso;
    iso << isotropic_ * Eigen::Matrix3d::Identity(), -skew(isotropicLever_), skew(isotropicLever_),
        second.trace() * Eigen::Matrix3d::Identity() - second;
    out_.stiffness += Eigen::Matrix<double, 6, 6>(symmetric_.selfadjointView<Eigen::Lower>()) + iso;
    // [g]x [r]x = r g^T - (g . r) I, summed.
    for (int side = 0; side < 2; ++side)
      out_.sideMoment[side] = leverTimesForce_[side] - leverTimesForce_[side].trace() * Eigen::Matrix3d::Identity();
  }

private:
  const NodeContacts& committed_;
  ImplicitPairResult& out_;
  Eigen::Vector3d centreA_;
  double increment_;
  std::size_t next_ = 0;  // the first committed contact not below the keys visited
  ContactLawConstants<double> trialLaw_, rateLaw_;
  Eigen::Vector3d forcePointSum_{0, 0, 0};
  double weight_ = 0.0;
  Eigen::Matrix3d leverTimesForce_[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};  // sum r g^T per side
  Eigen::Matrix<double, 6, 6> symmetric_ = Eigen::Matrix<double, 6, 6>::Zero();  // symmetric rank-one terms, lower triangle
  // The isotropic coefficient k and its moments over the levers r: sum k, sum k r, sum k r r^T (lower).
  double isotropic_ = 0.0;
  Eigen::Vector3d isotropicLever_{0, 0, 0};
  Eigen::Matrix3d isotropicSecond_ = Eigen::Matrix3d::Zero();
};

// The nodes of one side of a pair tested against the other side O's level set, phi(y, normal)
// with y in O's frame (normal: O's frame, set when phi < 0): the side's listed candidates, or when
// they are not listed every node in `region` (M's frame), listing those within the band. `blend`:
// O's planes (its frame), whose blended areas the nodes take (blendedArea); null: the projection
// on the contact plane.
template <class LevelSet>
void visitSide(Accumulator& acc, const ShapeModel& sm, const SidePoses& s, const Eigen::AlignedBox3d& region, std::uint32_t side,
               double areaShare, ImplicitCandidates& candidates, bool listing, double band, LevelSet&& levelSet,
               const PlanesInFrame* blend = nullptr, double sphereRadius = 0.0) {
  const double sign = side == 0 ? 1.0 : -1.0;
  const auto visit = [&](std::uint32_t rank) {
    const Eigen::Vector3d& x = sm.nodes.position[rank];
    const Eigen::Vector3d y = s.toO * x + s.shift;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    const double phi = levelSet(y, normal);
    if (listing && phi < band) candidates.keys.push_back(side << 31 | rank);
    if (!(phi < 0)) return;
    const Eigen::Vector3d n = s.RO * normal, ni = s.RM * sm.nodes.normal[rank];
    double area = facingArea(areaShare * sm.nodes.area[rank], -ni.dot(n));
    Eigen::Vector3d blendGradient = Eigen::Vector3d::Zero();  // d a / d(rel), world
    if (blend != nullptr) {
      const Eigen::Vector3d a = sm.nodes.area[rank] * (s.toO * sm.nodes.normal[rank]);
      BlendedArea<double> b;
      blendedArea(*blend, y.x(), y.y(), y.z(), phi, normal.x(), normal.y(), normal.z(), a.x(), a.y(), a.z(), areaShare, b);
      area = b.area;
      blendGradient = s.RO * Eigen::Vector3d(b.slopeX, b.slopeY, b.slopeZ) / -phi;
    }
    const Eigen::Vector3d rel = s.relMatrix * x + s.relShift;
    // Inside a sphere n = (x - c) / |x - c| turns as dn = kappa (I - n n^T) d(rel), kappa = 1 / |x - c|,
    // and the area a = A (-n_i . n) with it: d a / d(rel) = -A kappa (I - n n^T) n_i.
    // Turning the node's body by dtheta against the other side turns n_i against n: d a = -A (n_i x n) . dtheta.
    Eigen::Vector3d areaGradient = blendGradient, areaTurn = Eigen::Vector3d::Zero();
    const double curvature = sphereRadius > 0 ? 1.0 / (sphereRadius + phi) : 0.0;
    if (area > 0) {
      const double A = areaShare * sm.nodes.area[rank];
      // (Skipped below a hundredth of a radian between n_i and -n: a face on a face, where the
      // term is that fraction of a fraction d / r of the ones kept.)
      // (n_i x n in scalars: built as a vector and read back as one, it stalled on the store.)
      const double tx = ni.y() * n.z() - ni.z() * n.y(), ty = ni.z() * n.x() - ni.x() * n.z(), tz = ni.x() * n.y() - ni.y() * n.x();
      if (tx * tx + ty * ty + tz * tz > 1e-4) areaTurn = -A * Eigen::Vector3d(tx, ty, tz);
      if (curvature > 0) areaGradient = -A * curvature * (ni - n * n.dot(ni));
    }
    acc.add(side << 31 | rank, s.RM * x + s.cM, n, -phi, area, rel, sign, curvature, areaGradient, areaTurn, blend != nullptr);
  };
  if (listing) {
    sm.nodes.forEachNodeIn(region, [&](int rank) { visit(static_cast<std::uint32_t>(rank)); });
    return;
  }
  for (const std::uint32_t key : candidates.keys)
    if (key >> 31 == side) visit(key & 0x7fffffffu);
}

}  // namespace

Eigen::Matrix<double, 6, 6> shiftToPoint(const Eigen::Vector3d& origin, const Eigen::Vector3d& centroid) {
  Matrix6 T = Matrix6::Identity();
  T.block<3, 3>(0, 3) = -skew(origin - centroid);
  return T;
}

// The geometric part, the forces g on a held: a node moving with its body M moves its point p, so
//   side 0 (M = a): d M_a = [g]x [r]x dtheta_a,  d M_b = [g]x (dc_a - [r]x dtheta_a - dc_b)
//   side 1 (M = b): d M_a = [g]x (dc_a - dc_b + [r_b]x dtheta_b),  d M_b = -[g]x [r_b]x dtheta_b
// with r = p - c_a, r_b = p - c_b, summed over each side's contacts ([g]x [r_b]x = [g]x [r]x +
// [g]x [c_a - c_b]x), and the tangent takes their negatives.
Eigen::Matrix<double, 12, 12> pairTangent(const ImplicitPairResult& r, const Eigen::Vector3d& ca, const Eigen::Vector3d& cb) {
  Eigen::Matrix<double, 12, 12> K = Eigen::Matrix<double, 12, 12>::Zero();
  Eigen::Matrix<double, 6, 12> B = Eigen::Matrix<double, 6, 12>::Zero();
  B.leftCols<6>().setIdentity();
  B.rightCols<6>() = -shiftToPoint(ca, cb);
  K.noalias() = B.transpose() * r.stiffness * B;
  const Eigen::Matrix3d G0 = skew(r.sideForce[0]), G1 = skew(r.sideForce[1]);
  const Eigen::Matrix3d& H0 = r.sideMoment[0];
  const Eigen::Matrix3d H1 = r.sideMoment[1] + G1 * skew(ca - cb);
  // Blocks: translation of a at 0, rotation of a at 3, translation of b at 6, rotation of b at 9.
  K.block<3, 3>(3, 3) -= H0;
  K.block<3, 3>(9, 0) -= G0;
  K.block<3, 3>(9, 3) += H0;
  K.block<3, 3>(9, 6) += G0;
  K.block<3, 3>(3, 0) -= G1;
  K.block<3, 3>(3, 6) += G1;
  K.block<3, 3>(3, 9) -= H1;
  K.block<3, 3>(9, 9) += H1;
  return K;
}

// Built for each CPU version (cpu_versions.h) with everything it calls inlined into it
// (TESSERA_FLATTEN: the accumulator, the visits and the law would otherwise stay baseline code):
// 0.91 x the default test's time (docs/performance.md, "Built for the CPU").
TESSERA_CPU_VERSIONS TESSERA_FLATTEN
void evaluateImplicitPair(const ImplicitScene& scene, const PairContacts& pair, const NodeContacts& committed,
                          ImplicitCandidates& candidates, ImplicitPairResult& out) {
  const bool listing = !candidates.listed || candidates.a != pair.a || candidates.b != pair.b;
  if (listing) {
    candidates.a = pair.a;
    candidates.b = pair.b;
    candidates.keys.clear();
    candidates.listed = true;
  }
  const double band = scene.candidateBand;
  const RigidBodies& bodies = *scene.bodies;
  const IncrementStart& start = *scene.start;
  const int a = pair.a;
  const ShapeModel& sa = (*scene.shapes)[bodies.shape[a]];
  const Eigen::Matrix3d Ra = bodies.orientation[a].toRotationMatrix(), Ra0 = start.orientation[a].toRotationMatrix();
  const Eigen::Vector3d &ca = bodies.position[a], &ca0 = start.position[a];
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();

  if (pair.kind == PairKind::Bodies) {
    Accumulator acc(scene, pair, committed, 1.0, out);
    const int b = pair.b;
    const ShapeModel& sb = (*scene.shapes)[bodies.shape[b]];
    const Eigen::Matrix3d Rb = bodies.orientation[b].toRotationMatrix(), Rb0 = start.orientation[b].toRotationMatrix();
    const Eigen::Vector3d &cb = bodies.position[b], &cb0 = start.position[b];
    for (std::uint32_t side = 0; side < 2; ++side) {
      const ShapeModel& sm = side == 0 ? sa : sb;
      const ShapeModel& so = side == 0 ? sb : sa;
      const SidePoses s = side == 0 ? posesOf(Ra, ca, Rb, cb, Ra0, ca0, Rb0, cb0) : posesOf(Rb, cb, Ra, ca, Rb0, cb0, Ra0, ca0);
      // Each node's share of its area from its side (evaluateBodyPair): half, or one-way all or none.
      const double share = scene.parameters.sideAreaShare(static_cast<int>(side), sa.volume, sb.volume);
      if (share == 0) continue;
      Eigen::AlignedBox3d region = boxInNodeFrame(so.box, s);
      region.min().array() -= band;
      region.max().array() += band;
      // A convex other side: its planes in its own frame, for its exact level set (and blended areas).
      const PlanesInFrame planes(so.planes, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
      const bool blended = !so.planes.empty() && scene.parameters.area == ContactArea::Blended;
      visitSide(acc, sm, s, region, side, share, candidates, listing, band, [&](const Eigen::Vector3d& y, Eigen::Vector3d& normal) {
        if (so.planes.empty()) return so.meshLevelSet(y, normal);
        // A node is tested only for being inside (phi < 0) or, while listing, within the band.
        int best;
        const double phi = planes.phiBelow(y, listing ? band : 0.0, best);
        normal = so.planes[best].normal;
        return phi;
      }, blended ? &planes : nullptr);
    }
    acc.finish();
    return;
  }
  if (pair.kind == PairKind::Sphere) {
    const int k = -1 - pair.b;
    const SphereObstacle& sphere = (*scene.spheres)[k];
    Accumulator acc(scene, pair, committed, sphere.stiffnessFactor, out);
    const SidePoses s = posesOf(Ra, ca, I, sphere.center, Ra0, ca0, I, start.sphereCentre[k]);
    const Eigen::Vector3d centre = Ra.transpose() * (sphere.center - ca);
    const Eigen::AlignedBox3d region(centre.array() - sphere.radius - band, centre.array() + sphere.radius + band);
    visitSide(acc, sa, s, region, 0, 1.0, candidates, listing, band, [&](const Eigen::Vector3d& y, Eigen::Vector3d& normal) {
      const double distance = y.norm();
      normal = distance > 0 ? Eigen::Vector3d(y / distance) : Eigen::Vector3d::UnitZ();
      return distance - sphere.radius;
    }, nullptr, sphere.radius);
    acc.finish();
    return;
  }
  const PlaneObstacle& plane = (*scene.planes)[-1 - pair.b - static_cast<int>(scene.spheres->size())];
  Accumulator acc(scene, pair, committed, 1.0, out);
  const SidePoses s = posesOf(Ra, ca, I, plane.point, Ra0, ca0, I, plane.point);
  visitSide(acc, sa, s, sa.nodes.box, 0, 1.0, candidates, listing, band, [&](const Eigen::Vector3d& y, Eigen::Vector3d& normal) {
    normal = plane.normal;
    return plane.normal.dot(y);
  });
  acc.finish();
}

}  // namespace tessera
