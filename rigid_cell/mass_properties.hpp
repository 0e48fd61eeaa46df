// Volume, first and second moments of a rigid cell about its node, summed over simplices that share the node as a
// vertex (Květoň §8.2.2, Fig. 3.1b): a Voronoi cell is convex and holds its node, so the simplices spanned by the
// node and a fan of each face fill it without overlap. The simplex moments are exact (Tonon 2005, Květoň
// (8.11)-(8.12)): ∫ x xᵀ dV = V/20 (Σᵢ xᵢxᵢᵀ + s sᵀ) for a tetrahedron, V/12 (…) for a triangle, s = Σᵢ xᵢ, with
// the vertices xᵢ taken about the node (the node's own term is zero).
#pragma once
#include <Eigen/Core>
#include <cmath>

#include "engine/dim.hpp"

namespace mc::rigid_cell {

template <int D>
struct MassProperties {
  double volume = 0;                                                         // [m³]; 2D: [m²] × 1 m
  Vec<D> first = Vec<D>::Zero();                                             // ∫ r dV [m⁴]
  Eigen::Matrix<double, D, D> second = Eigen::Matrix<double, D, D>::Zero();  // ∫ r rᵀ dV [m⁵]

  Vec<D> centroid() const { return first / volume; }  // about the node
  // The inertia tensor per unit density about the node, Květoň (8.8)-(8.10): ∫(|r|² I − r rᵀ) dV. In 2D the
  // 1 × 1 polar moment ∫|r|² dA about the out-of-plane axis.
  Eigen::Matrix<double, Dim<D>::rot, Dim<D>::rot> inertia() const {
    if constexpr (D == 2) {
      return Eigen::Matrix<double, 1, 1>(second.trace());
    } else {
      return second.trace() * Eigen::Matrix3d::Identity() - second;
    }
  }
  // The cell's mass matrix about its node for a density ρ, Květoň (8.6)-(8.8): m on the translations, the inertia
  // tensor on the rotations, and between them the additional momentum (8.7) of a centroid that is not the node,
  // S_m = −[m Δ]× (the kinetic energy ½∫ρ|u̇ + θ̇ × r|² dV couples u̇ and θ̇ through ∫ρ r dV = m Δ). 2D: (x, y, θ).
  Eigen::Matrix<double, D + Dim<D>::rot, D + Dim<D>::rot> mass_matrix(double density) const {
    constexpr int n = D + Dim<D>::rot;
    Eigen::Matrix<double, n, n> M = Eigen::Matrix<double, n, n>::Zero();
    const double m = density * volume;
    const Vec<D> s = density * first;  // m Δ
    M.template topLeftCorner<D, D>() = m * Eigen::Matrix<double, D, D>::Identity();
    M.template bottomRightCorner<Dim<D>::rot, Dim<D>::rot>() = density * inertia();
    Eigen::Matrix<double, D, Dim<D>::rot> S;
    if constexpr (D == 2) {
      S << -s.y(), s.x();
    } else {
      S << 0, s.z(), -s.y(), -s.z(), 0, s.x(), s.y(), -s.x(), 0;
    }
    M.template topRightCorner<D, Dim<D>::rot>() = S;
    M.template bottomLeftCorner<Dim<D>::rot, D>() = S.transpose();
    return M;
  }
  MassProperties& operator+=(const MassProperties& o) {
    volume += o.volume;
    first += o.first;
    second += o.second;
    return *this;
  }
};

// The triangle (node, p, q), p and q about the node.
inline MassProperties<2> simplex(const Vec<2>& p, const Vec<2>& q) {
  MassProperties<2> m;
  m.volume = 0.5 * std::abs(p.x() * q.y() - p.y() * q.x());
  const Vec<2> s = p + q;
  m.first = m.volume * s / 3.0;
  m.second = m.volume / 12.0 * (p * p.transpose() + q * q.transpose() + s * s.transpose());
  return m;
}

// The tetrahedron (node, p, q, r), p, q and r about the node.
inline MassProperties<3> simplex(const Vec<3>& p, const Vec<3>& q, const Vec<3>& r) {
  MassProperties<3> m;
  m.volume = std::abs(p.dot(q.cross(r))) / 6.0;
  const Vec<3> s = p + q + r;
  m.first = m.volume * s / 4.0;
  m.second = m.volume / 20.0 * (p * p.transpose() + q * q.transpose() + r * r.transpose() + s * s.transpose());
  return m;
}

// The pyramid over one face of a cell, its apex at the node: the face's vertices in order around it, about the
// node (2D: a face is a segment, two vertices).
template <int D, class Vertices>
MassProperties<D> pyramid(const Vertices& face) {
  MassProperties<D> m;
  if constexpr (D == 2) {
    m += simplex(face[0], face[1]);
  } else {
    for (std::size_t i = 1; i + 1 < face.size(); ++i) m += simplex(face[0], face[i], face[i + 1]);
  }
  return m;
}

}  // namespace mc::rigid_cell
