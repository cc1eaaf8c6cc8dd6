#include "solver/implicit_contacts.h"

#include "solver/node_contact_law.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

// One side of a pair: the node's body M and the other side O, at the trial configuration and at
// the increment's start. A node at body-frame position x_b is at p = R_M x_b + c_M (world) and at
// y = R_O^T (p - c_O) in O's frame; its displacement relative to O over the increment is
// rel = R_O (y - y0): the node's motion less that of O's material point it was at.
struct SidePoses {
  Eigen::Matrix3d RM, RO, toO, toO0;
  Eigen::Vector3d cM, shift, shift0;
};

SidePoses posesOf(const Eigen::Matrix3d& RM, const Eigen::Vector3d& cM, const Eigen::Matrix3d& RO, const Eigen::Vector3d& cO,
                  const Eigen::Matrix3d& RM0, const Eigen::Vector3d& cM0, const Eigen::Matrix3d& RO0, const Eigen::Vector3d& cO0) {
  return {RM, RO, RO.transpose() * RM, RO0.transpose() * RM0, cM, RO.transpose() * (cM - cO), RO0.transpose() * (cM0 - cO0)};
}

// The region of M's frame that O's box (in O's frame) covers.
Eigen::AlignedBox3d boxInNodeFrame(const Eigen::AlignedBox3d& otherBox, const SidePoses& s) {
  Eigen::AlignedBox3d region;
  for (int corner = 0; corner < 8; ++corner)
    region.extend(s.toO.transpose() * (otherBox.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)) - s.shift));
  return region;
}

// The law over a pair's contacts as they are found, and what they add up to.
class Accumulator {
public:
  Accumulator(const ImplicitScene& scene, const PairContacts& pair, const NodeContacts& committed, double stiffnessFactor,
              ImplicitPairResult& out)
      : committed_(committed), out_(out), centreA_(scene.bodies->position[pair.a]), increment_(scene.increment),
        trialLaw_(ContactLawConstants<double>::of(scene.parameters, stiffnessFactor * scene.kn, stiffnessFactor * scene.kt, 1.0)),
        rateLaw_(ContactLawConstants<double>::of(scene.parameters, stiffnessFactor * scene.kn, stiffnessFactor * scene.kt,
                                                 scene.increment)) {
    NodeContacts kept = std::move(out_.contacts);  // its capacity, not its values
    out_ = ImplicitPairResult{};
    out_.contacts = std::move(kept);
    out_.contacts.clear();
  }

  // A node inside the other side: its key, world position p, the other side's outward normal n
  // (world), its depth, effective area a (0: facing away), displacement relative to the other
  // side over the increment, and sign +1 for a node of a, -1 for a node of b.
  void add(std::uint32_t key, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double depth, double area,
           const Eigen::Vector3d& rel, double sign) {
    // The committed spring, area and energy of this node contact (none: a new contact, area -1).
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    double areaBefore = -1.0, energyBefore = 0.0;
    const auto found = std::lower_bound(committed_.key.begin(), committed_.key.end(), key);
    if (found != committed_.key.end() && *found == key) {
      const NodeContact c = committed_[static_cast<std::size_t>(found - committed_.key.begin())];
      u = c.spring;
      areaBefore = c.area;
      energyBefore = c.energy;
    }
    // The law of the explicit step with v dt = rel: the spring turned onto the tangent plane plus
    // the tangential part of rel, capped at mu f_n; the normal viscosity at the approach rate.
    const double vn = rel.dot(n), rate = increment_ > 0 ? vn / increment_ : 0.0;
    double ux = u.x(), uy = u.y(), uz = u.z();
    const double turnedDotTrial = trialSpring(trialLaw_, n.x(), n.y(), n.z(), rel.x(), rel.y(), rel.z(), vn, ux, uy, uz);
    const Eigen::Vector3d trial(ux, uy, uz);
    const SpringUpdate<double> update = capSpring(rateLaw_, depth, area, rate, turnedDotTrial, ux, uy, uz);
    const ContactForce<double> f = contactForce(rateLaw_, n.x(), n.y(), n.z(), depth, area, rate, ux, uy, uz);
    const Eigen::Vector3d force(f.fx, f.fy, f.fz);

    // K = -df / d(rel) (docs/physics.md, "Implicit method"):
    //   normal     (k_n a + eta_n a / dt) n n^T                       while f_n > 0
    //   sticking   k_t a (I - n n^T)
    //   sliding    mu f_n / |s| (I - s^ s^T)(I - n n^T) - mu (k_n a + eta_n a / dt) s^ n^T
    // (s: the trial spring; sliding, f_t = -mu f_n s^). Terms of the order of the force times a
    // rotation (the normal turning with the other side, the lever turning with the body) are left
    // out: they are f / (k a r) = d / r of the ones kept.
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    if (f.fn > 0) {
      const NormalForce<double> nf = normalForce(rateLaw_, depth, area, rate);
      const double kNormal = nf.kna + (increment_ > 0 ? rateLaw_.viscosity * area / increment_ : 0.0);
      const Eigen::Matrix3d nn = n * n.transpose(), tangent = Eigen::Matrix3d::Identity() - nn;
      K = kNormal * nn;
      const double length = trial.norm();
      if (update.sliding > 0 && length > 0) {
        const Eigen::Vector3d s = trial / length;
        K += rateLaw_.friction * f.fn / length * (Eigen::Matrix3d::Identity() - s * s.transpose()) * tangent;
        K -= rateLaw_.friction * kNormal * s * n.transpose();
      } else {
        K += nf.kta * tangent;
      }
    }
    const Eigen::Vector3d r = p - centreA_, g = sign * force;
    out_.force.head<3>() += g;
    out_.force.tail<3>() += r.cross(g);
    Eigen::Matrix<double, 3, 6> G;
    G << Eigen::Matrix3d::Identity(), -skew(r);
    out_.stiffness.noalias() += G.transpose() * K * G;
    out_.normalForceA += sign * f.fn * n;
    forcePointSum_ += f.fn * r;
    weight_ += f.fn;
    out_.forceScale += force.norm();
    out_.maxDepth = std::max(out_.maxDepth, depth);
    out_.tally.elastic += f.stored;
    out_.tally.friction += update.friction;
    out_.tally.viscous += update.viscous;
    out_.tally.sliding += static_cast<int>(update.sliding);
    // Stored energy proportional to the area: what the change of area alone removed (as the
    // explicit step books it, ContactTally::projection).
    const double perArea = 0.5 * rateLaw_.perAreaNormal * depth * depth + 0.5 * rateLaw_.perAreaTangent * (ux * ux + uy * uy + uz * uz);
    double removed = areaBefore > 0 ? perArea * (areaBefore - area) : 0.0;
    if (areaBefore == 0) removed = -f.stored;
    if (!(area > 0)) removed = energyBefore;
    out_.tally.projection += removed;
    out_.contacts.push_back({key, Eigen::Vector3d(ux, uy, uz), f.stored, area});
  }

  void finish() { out_.forcePoint = weight_ > 0 ? Eigen::Vector3d(centreA_ + forcePointSum_ / weight_) : Eigen::Vector3d::Zero(); }

private:
  const NodeContacts& committed_;
  ImplicitPairResult& out_;
  Eigen::Vector3d centreA_;
  double increment_;
  ContactLawConstants<double> trialLaw_, rateLaw_;
  Eigen::Vector3d forcePointSum_{0, 0, 0};
  double weight_ = 0.0;
};

// m^2, a node's share of its area projected on the contact plane, 0 facing away (as the explicit step).
double facingArea(double share, double projection) { return share * (projection > 0 ? projection : 0.0); }

// Every node of M in `region` (M's frame) tested against O's level set, phi(y, normal) with y in
// O's frame (normal: O's frame, set when phi < 0).
template <class LevelSet>
void visitSide(Accumulator& acc, const ShapeModel& sm, const SidePoses& s, const Eigen::AlignedBox3d& region, std::uint32_t side,
               double areaShare, LevelSet&& levelSet) {
  const double sign = side == 0 ? 1.0 : -1.0;
  sm.nodes.forEachNodeIn(region, [&](int rank) {
    const Eigen::Vector3d& x = sm.nodes.position[rank];
    const Eigen::Vector3d y = s.toO * x + s.shift;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    const double phi = levelSet(y, normal);
    if (!(phi < 0)) return;
    const Eigen::Vector3d n = s.RO * normal;
    const double area = facingArea(areaShare * sm.nodes.area[rank], -(s.RM * sm.nodes.normal[rank]).dot(n));
    const Eigen::Vector3d rel = s.RO * (y - (s.toO0 * x + s.shift0));
    acc.add(side << 31 | static_cast<std::uint32_t>(rank), s.RM * x + s.cM, n, -phi, area, rel, sign);
  });
}

}  // namespace

Eigen::Matrix<double, 6, 6> shiftToPoint(const Eigen::Vector3d& origin, const Eigen::Vector3d& centroid) {
  Matrix6 T = Matrix6::Identity();
  T.block<3, 3>(0, 3) = -skew(origin - centroid);
  return T;
}

void evaluateImplicitPair(const ImplicitScene& scene, const PairContacts& pair, const NodeContacts& committed,
                          ImplicitPairResult& out) {
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
      // Half of each node's area from either side (evaluateBodyPair).
      visitSide(acc, sm, s, boxInNodeFrame(so.box, s), side, 0.5, [&](const Eigen::Vector3d& y, Eigen::Vector3d& normal) {
        if (so.planes.empty()) return so.meshLevelSet(y, normal);
        // The exact level set of a convex polyhedron: max_f (n_f . y - d_f), the first plane of
        // largest value giving the normal.
        double phi = -std::numeric_limits<double>::infinity();
        for (const FacePlane& f : so.planes) {
          const double v = f.normal.dot(y) - f.offset;
          if (v > phi) {
            phi = v;
            normal = f.normal;
          }
        }
        return phi;
      });
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
    const Eigen::AlignedBox3d region(centre.array() - sphere.radius, centre.array() + sphere.radius);
    visitSide(acc, sa, s, region, 0, 1.0, [&](const Eigen::Vector3d& y, Eigen::Vector3d& normal) {
      const double distance = y.norm();
      normal = distance > 0 ? Eigen::Vector3d(y / distance) : Eigen::Vector3d::UnitZ();
      return distance - sphere.radius;
    });
    acc.finish();
    return;
  }
  const PlaneObstacle& plane = (*scene.planes)[-1 - pair.b - static_cast<int>(scene.spheres->size())];
  Accumulator acc(scene, pair, committed, 1.0, out);
  const SidePoses s = posesOf(Ra, ca, I, plane.point, Ra0, ca0, I, plane.point);
  visitSide(acc, sa, s, sa.nodes.box, 0, 1.0, [&](const Eigen::Vector3d& y, Eigen::Vector3d& normal) {
    normal = plane.normal;
    return plane.normal.dot(y);
  });
  acc.finish();
}

}  // namespace tessera
