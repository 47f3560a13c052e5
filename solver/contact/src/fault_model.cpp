#include "ugs/contact/fault_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::contact {
namespace {

using V3 = std::array<double, 3>;

V3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }

std::string fault_group_of(const Mesh& mesh, const ElementBlock& b) {
  const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
  if (!e) return {};
  for (int p : e->physicals)
    if (const PhysicalGroup* g = mesh.find_physical_tag(b.entity_dim, p); g && g->name.rfind("fault:", 0) == 0)
      return g->name.substr(6);
  return {};
}

struct FaceKey {
  std::array<std::uint32_t, 3> n;
  bool operator==(const FaceKey& o) const { return n == o.n; }
};
struct FaceHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = k.n[0];
    h = h * 0x9E3779B97F4A7C15ull ^ k.n[1];
    h = h * 0x9E3779B97F4A7C15ull ^ k.n[2];
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};
FaceKey face_key(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  FaceKey k{{a, b, c}};
  std::sort(k.n.begin(), k.n.end());
  return k;
}

struct PairKey {
  std::int32_t fault;
  std::uint32_t s1, s2;
  bool operator<(const PairKey& o) const { return std::tie(fault, s1, s2) < std::tie(o.fault, o.s1, o.s2); }
};

// Union-find over mesh nodes, for the cycles of twin constraints at junctions.
struct Dsu {
  std::vector<std::uint32_t> parent;
  explicit Dsu(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    if (b < a) std::swap(a, b);
    parent[b] = a;
    return true;
  }
};

}  // namespace

std::array<double, 9> fault_frame(const Point3& n) {
  V3 t1 = cross({n[0], n[1], n[2]}, {0, 0, 1});
  const double l = norm(t1);
  if (l < 1e-6) t1 = {1, 0, 0};  // horizontal fault: strike along x
  else t1 = {t1[0] / l, t1[1] / l, t1[2] / l};
  const V3 t2 = cross({n[0], n[1], n[2]}, t1);
  return {t1[0], t2[0], n[0], t1[1], t2[1], n[1], t1[2], t2[2], n[2]};
}

ConstraintFrame constraint_frame(const Point3& n, std::uint8_t fixed1, std::uint8_t fixed2) {
  ConstraintFrame f;
  f.R = fault_frame(n);
  const unsigned free_mask = 7u & ~static_cast<unsigned>(fixed1 & fixed2);
  if (free_mask == 7) return f;
  if (free_mask == 0) {
    f.active = 0;
    return f;
  }
  const V3 nv{n[0], n[1], n[2]};
  auto axis = [](int c) {
    V3 e{0, 0, 0};
    e[c] = 1;
    return e;
  };
  auto unit = [](const V3& v) {
    const double l = norm(v);
    return V3{v[0] / l, v[1] / l, v[2] / l};
  };
  std::vector<int> in_s, in_f;  // free and prescribed axes
  for (int c = 0; c < 3; ++c) ((free_mask >> c) & 1 ? in_s : in_f).push_back(c);
  V3 m{0, 0, 0};
  for (int c : in_s) m[c] = nv[c];
  V3 normal, ta, tb;    // the normal slot and the two tangents
  bool normal_active, ta_active, tb_active;
  if (norm(m) > kNormalInFree) {
    normal = unit(m);  // turned into m itself below
    normal_active = true;
    if (in_s.size() == 2) {
      ta = cross(normal, axis(in_f[0]));  // in S (normal to the prescribed axis) and normal to m
      tb = axis(in_f[0]);
      ta_active = true, tb_active = false;
    } else {  // S = one axis, the normal slot itself
      ta = axis(in_f[0]), tb = axis(in_f[1]);
      ta_active = tb_active = false;
    }
  } else {
    V3 mf{0, 0, 0};
    for (int c : in_f) mf[c] = nv[c];
    normal = unit(mf);
    normal_active = false;
    if (in_s.size() == 2) {  // one prescribed axis: the normal is along it, S is its complement
      ta = axis(in_s[0]), tb = axis(in_s[1]);
      ta_active = tb_active = true;
    } else {
      ta = axis(in_s[0]);
      tb = cross(normal, ta);  // normal to S and to the normal slot: a prescribed direction
      ta_active = true, tb_active = false;
    }
  }
  // Slots: the pairing of (ta, tb) with (strike, dip) that keeps them closest, each turned to its
  // fault-frame tangent.
  const V3 t1{f.R[0], f.R[3], f.R[6]}, t2{f.R[1], f.R[4], f.R[7]};
  if (std::abs(dot(tb, t1)) + std::abs(dot(ta, t2)) > std::abs(dot(ta, t1)) + std::abs(dot(tb, t2))) {
    std::swap(ta, tb);
    std::swap(ta_active, tb_active);
  }
  if (dot(ta, t1) < 0) ta = {-ta[0], -ta[1], -ta[2]};
  if (dot(tb, t2) < 0) tb = {-tb[0], -tb[1], -tb[2]};
  // An active normal slot is m = P_S n itself: the constraint row m . g = n . g is the fault's own
  // normal gap (g lies in S) and the force of a normal traction sigma_n, A sigma_n m, is the free
  // part of A sigma_n n, so lambda_n stays the fault's normal traction (and lambda_n + p_f its
  // effective normal traction). The active tangent is normal to m within S, hence to n: a shear
  // direction of the fault.
  if (normal_active) normal = m;
  for (int c = 0; c < 3; ++c) f.R[3 * c] = ta[c], f.R[3 * c + 1] = tb[c], f.R[3 * c + 2] = normal[c];
  f.active = static_cast<std::uint8_t>((ta_active ? 1 << kStrike : 0) | (tb_active ? 1 << kDip : 0) | (normal_active ? 1 << kNormal : 0));
  return f;
}

InitialFaultState geostatic_fault_state(const mech::InitialState& init) {
  InitialFaultState s;
  s.total_stress = [init](const Point3& x, double biot, const std::array<double, 2>& k, const GasColumn& gas) {
    fem::Vec6 sig = init.effective_stress(x[2], biot, k, gas);
    const double p = init.pore_pressure(x[2], gas);
    for (int k = 0; k < 3; ++k) sig[k] -= biot * p;
    return sig;
  };
  s.pressure = [init](const Point3& x, const GasColumn& gas) { return init.pore_pressure(x[2], gas); };
  return s;
}

FaultModel build_fault_model(const Mesh& mesh, const CaseFile& cs, const mech::Model& model, const InitialFaultState& init) {
  FaultModel fm;
  // 1. Faults: every fault:<name> group holding interface elements needs a [[fault]] entry and
  //    every [[fault]] entry a group (faults in case-file order).
  std::map<std::string, std::size_t> mesh_faults;  // name -> interface elements
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Prism || b.size() == 0) continue;
    const std::string name = fault_group_of(mesh, b);
    if (name.empty())
      throw InputError("mesh", fmt::format("interface element {} (6-node prism) belongs to no fault:<name> group", b.tags[0]));
    mesh_faults[name] += b.size();
  }
  std::string mesh_list;
  for (const auto& [n, c] : mesh_faults) mesh_list += (mesh_list.empty() ? "" : ", ") + n;
  std::map<std::string, std::int32_t> index;
  for (const auto& f : cs.faults) {
    if (index.count(f.name)) throw InputError(f.where, fmt::format("fault '{}' is described twice", f.name));
    if (!mesh_faults.count(f.name))
      throw InputError(f.where, fmt::format("fault '{}' is not in the mesh: no interface elements in group fault:{} (the "
                                            "mesh has: {})", f.name, f.name, mesh_list.empty() ? "none" : mesh_list));
    FaultProperties p;
    p.name = f.name;
    p.where = f.where;
    p.cohesion = f.cohesion_Pa;
    p.friction_deg = f.friction_deg;
    if (!(f.friction_deg > 0 && f.friction_deg < 90))
      throw InputError(f.where, fmt::format("fault '{}': friction angle {} outside (0, 90) degrees", f.name, f.friction_deg));
    if (!(f.cohesion_Pa >= 0)) throw InputError(f.where, fmt::format("fault '{}': negative cohesion", f.name));
    p.mu = std::tan(f.friction_deg * M_PI / 180.0);
    index[f.name] = static_cast<std::int32_t>(fm.faults.size());
    fm.faults.push_back(p);
  }
  for (const auto& [n, c] : mesh_faults)
    if (!index.count(n))
      throw InputError(cs.path, fmt::format("the mesh has {} interface elements in fault:{} but the case has no [[fault]] "
                                            "entry named '{}' (cohesion_MPa, friction_deg)", c, n, n));

  // 2. Interface elements per fault (case order, then mesh block order): twins and geometry.
  struct Element {
    std::int32_t fault;
    std::uint64_t tag;
    std::array<std::uint32_t, 6> n;
    V3 normal;  // unit, side 1 -> side 2
    double area;
    std::int64_t tet1 = -1, tet2 = -1;
  };
  std::vector<Element> elems;
  for (std::size_t fi = 0; fi < fm.faults.size(); ++fi)
    for (const auto& b : mesh.blocks) {
      if (b.type != ElementType::Prism || fault_group_of(mesh, b) != fm.faults[fi].name) continue;
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto e = b.element(i);
        Element el;
        el.fault = static_cast<std::int32_t>(fi);
        el.tag = b.tags[i];
        std::copy(e.begin(), e.end(), el.n.begin());
        const Point3 &a = mesh.nodes[e[0]], &bb = mesh.nodes[e[1]], &c = mesh.nodes[e[2]];
        const V3 nv = cross(sub(bb, a), sub(c, a));
        const double h = std::max({norm(sub(bb, a)), norm(sub(c, a)), norm(sub(c, bb))});
        el.area = 0.5 * norm(nv);
        if (!(el.area > 1e-12 * h * h) || !(h > 0))
          throw InputError("mesh", fmt::format("interface element {} of fault:{} is degenerate (zero area)", el.tag,
                                               fm.faults[fi].name));
        for (int k = 0; k < 3; ++k) {
          const double d = norm(sub(mesh.nodes[e[k]], mesh.nodes[e[k + 3]]));
          if (d > 1e-6 * h)
            throw InputError("mesh", fmt::format("interface element {} of fault:{}: node {} has no twin (node {} lies {:.3g} m "
                                                 "away); interface elements need nodes 4-6 at the points of nodes 1-3, as "
                                                 "ugs-faultinsert writes them", el.tag, fm.faults[fi].name,
                                                 mesh.node_tags[e[k]], mesh.node_tags[e[k + 3]], d));
        }
        el.normal = {nv[0] / (2 * el.area), nv[1] / (2 * el.area), nv[2] / (2 * el.area)};
        elems.push_back(el);
      }
    }

  // 3. The tetrahedra on each side (stiffness scale, Biot coefficient): the side-1 face belongs to
  //    a tetrahedron on the -n side, the side-2 face to one on the +n side.
  std::unordered_map<FaceKey, std::array<std::int64_t, 2>, FaceHash> faces;
  faces.reserve(4 * elems.size());
  for (const auto& el : elems) {
    faces.emplace(face_key(el.n[0], el.n[1], el.n[2]), std::array<std::int64_t, 2>{-1, -1});
    faces.emplace(face_key(el.n[3], el.n[4], el.n[5]), std::array<std::int64_t, 2>{-1, -1});
  }
  static const int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (std::size_t t = 0; t < model.tets.size(); ++t) {
    const auto& tn = model.tets[t];
    for (const auto& f : kFaces) {
      auto it = faces.find(face_key(tn[f[0]], tn[f[1]], tn[f[2]]));
      if (it == faces.end()) continue;
      auto& slot = it->second;
      (slot[0] < 0 ? slot[0] : slot[1]) = static_cast<std::int64_t>(t);
    }
  }
  auto opposite = [&](std::int64_t t, const FaceKey& k) {
    for (auto v : model.tets[t])
      if (v != k.n[0] && v != k.n[1] && v != k.n[2]) return v;
    return model.tets[t][0];
  };
  for (auto& el : elems) {
    const Point3& x0 = mesh.nodes[el.n[0]];
    for (int side = 0; side < 2; ++side) {
      const FaceKey k = side == 0 ? face_key(el.n[0], el.n[1], el.n[2]) : face_key(el.n[3], el.n[4], el.n[5]);
      std::int64_t found = -1;
      for (std::int64_t t : faces.at(k)) {
        if (t < 0) continue;
        const double s = dot(sub(mesh.nodes[opposite(t, k)], x0), el.normal);
        if ((side == 0 && s < 0) || (side == 1 && s > 0)) found = t;
      }
      if (found < 0)
        throw InputError("mesh", fmt::format("interface element {} of fault:{}: its side-{} face is not a face of a "
                                             "tetrahedron on that side (the element does not come from ugs-faultinsert, or "
                                             "its nodes are not in side order)", el.tag, fm.faults[el.fault].name, side + 1));
      (side == 0 ? el.tet1 : el.tet2) = found;
    }
  }
  // (a Model made without build_model may lack the gas columns: water then)
  auto gas_of = [&](std::int32_t mat) {
    return static_cast<std::size_t>(mat) < model.material_gas.size() ? model.material_gas[mat] : GasColumn{};
  };
  auto tet_info = [&](std::int64_t t, double face_area, double& k, double& biot) {
    const auto& tn = model.tets[t];
    const fem::Material& m = model.materials[model.tet_material[t]];
    const double zc = 0.25 * (model.x[tn[0]][2] + model.x[tn[1]][2] + model.x[tn[2]][2] + model.x[tn[3]][2]);
    fem::Mat6 D;
    if (m.law == fem::Law::Linear) D = m.D_linear;
    else D = m.elastic_D(model.initial.effective_vertical_stress(zc, m.biot, gas_of(model.tet_material[t])) * 1e-6);
    const double E = std::max({D[0], D[7], D[14]});
    const double vol = std::abs(tet_signed_volume(model.x[tn[0]], model.x[tn[1]], model.x[tn[2]], model.x[tn[3]]));
    k = E / (3 * vol / face_area);
    biot = m.biot;
  };

  // 4. Node pairs.
  std::map<PairKey, std::size_t> pair_of;
  std::vector<V3> nsum;
  std::vector<double> ksum, bsum;
  std::vector<std::array<double, 2>> rsum;  // stress ratios (k_Hmax, k_hmin) of side 1, area-weighted
  std::vector<std::map<std::int32_t, double>> side1_area;  // side-1 area by material (the pair's gas column)
  std::vector<std::map<std::uint32_t, char>> tips(fm.faults.size());
  for (const auto& el : elems) {
    double k1, k2, b1, b2;
    tet_info(el.tet1, el.area, k1, b1);
    tet_info(el.tet2, el.area, k2, b2);
    FaultProperties& f = fm.faults[el.fault];
    ++f.elements;
    f.area += el.area;
    int paired = 0;  // corners of the triangle that are node pairs
    for (int c = 0; c < 3; ++c) paired += el.n[c] != el.n[c + 3];
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t s1 = el.n[c], s2 = el.n[c + 3];
      if (s1 == s2) {
        tips[el.fault][s1] = 1;
        continue;
      }
      auto [it, fresh] = pair_of.emplace(PairKey{el.fault, s1, s2}, fm.pairs.size());
      if (fresh) {
        NodePair p;
        p.side1 = s1;
        p.side2 = s2;
        p.tag1 = mesh.node_tags[s1];
        p.tag2 = mesh.node_tags[s2];
        p.fault = el.fault;
        p.x = mesh.nodes[s1];
        fm.pairs.push_back(p);
        nsum.push_back({0, 0, 0});
        ksum.push_back(0);
        bsum.push_back(0);
        rsum.push_back({0, 0});
        side1_area.emplace_back();
      }
      const std::size_t q = it->second;
      const double a = el.area / 3;
      fm.pairs[q].area += a;
      fm.pairs[q].reported_area += el.area / paired;
      for (int d = 0; d < 3; ++d) nsum[q][d] += a * el.normal[d];
      ksum[q] += a * 0.5 * (k1 + k2);
      bsum[q] += a * b1;
      const auto& r1 = model.material_k[model.tet_material[el.tet1]];
      rsum[q][0] += a * r1[0], rsum[q][1] += a * r1[1];
      side1_area[q][model.tet_material[el.tet1]] += a;
    }
  }
  for (std::size_t fi = 0; fi < fm.faults.size(); ++fi) fm.faults[fi].tip_nodes = tips[fi].size();

  Dsu dsu(mesh.num_nodes());
  for (std::size_t q = 0; q < fm.pairs.size(); ++q) {
    NodePair& p = fm.pairs[q];
    ++fm.faults[p.fault].pairs;
    const double l = norm(nsum[q]);
    const V3 n = l > 0 ? V3{nsum[q][0] / l, nsum[q][1] / l, nsum[q][2] / l} : V3{0, 0, 1};
    p.fixed1 = model.fixed[p.side1];
    p.fixed2 = model.fixed[p.side2];
    // The constraint frame: exactly the free part of the jump carries multipliers.
    const ConstraintFrame cf = constraint_frame(n, p.fixed1, p.fixed2);
    p.R = cf.R;
    p.active = cf.active;
    p.k = ksum[q] / p.area;
    const double biot = bsum[q] / p.area;
    std::int32_t mat1 = side1_area[q].begin()->first;  // the largest share (the first material on a tie)
    for (const auto& [mat, a] : side1_area[q])
      if (a > side1_area[q].at(mat1)) mat1 = mat;
    const GasColumn gas = gas_of(mat1);
    const fem::Vec6 s = init.total_stress(p.x, biot, {rsum[q][0] / p.area, rsum[q][1] / p.area}, gas);
    // Traction t = sigma n (thesis Voigt order xx yy zz yz xz xy), in the pair's frame. A held
    // tangent slot of a reduced frame is a prescribed direction: its traction is the support's
    // reaction, not the fault's, and is reported as 0 (it enters no equation but its own hold).
    const V3 t = {s[0] * n[0] + s[5] * n[1] + s[4] * n[2], s[5] * n[0] + s[1] * n[1] + s[3] * n[2],
                  s[4] * n[0] + s[3] * n[1] + s[2] * n[2]};
    const bool reduced = (p.fixed1 & p.fixed2) != 0;
    for (int j = 0; j < 3; ++j) {
      p.lambda0[j] = p.R[j] * t[0] + p.R[3 + j] * t[1] + p.R[6 + j] * t[2];
      if (reduced && p.active != 0 && j < 2 && !((p.active >> j) & 1)) p.lambda0[j] = 0;
    }
    if (reduced && p.active != 0) p.lambda0[2] = dot(n, t);  // the fault's normal traction
    p.p0 = init.pressure(p.x, gas);
    if (reduced) ++fm.boundary_pairs;
    if (!p.frictional()) ++fm.inactive_pairs;
    if (!dsu.unite(p.side1, p.side2)) {
      p.redundant = true;
      ++fm.redundant_pairs;
    }
  }
  // Junctions: the pairs whose twins are joined to a cycle's (the copies of one node where faults
  // meet), numbered in the order of their first closing pair.
  std::map<std::uint32_t, std::int32_t> junction_of;
  for (const NodePair& p : fm.pairs)
    if (p.redundant) junction_of.emplace(dsu.find(p.side1), static_cast<std::int32_t>(junction_of.size()));
  for (NodePair& p : fm.pairs) {
    const auto it = junction_of.find(dsu.find(p.side1));
    if (it != junction_of.end()) p.junction = it->second;
  }
  fm.junctions = junction_of.size();

  // 5. The output surface.
  FaultSurface& S = fm.surface;
  for (std::size_t fi = 0; fi < fm.faults.size(); ++fi) {
    const int ent = S.mesh.entity_for_physical(2, "fault:" + fm.faults[fi].name);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> node_of;
    for (const auto& el : elems) {
      if (el.fault != static_cast<std::int32_t>(fi)) continue;
      std::array<std::uint32_t, 3> tri;
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t s1 = el.n[c], s2 = el.n[c + 3];
        auto [it, fresh] = node_of.emplace(std::make_pair(s1, s2), 0u);
        if (fresh) {
          it->second = S.mesh.add_node(mesh.nodes[s1], mesh.node_tags[s1]);
          S.node_pair.push_back(s1 == s2 ? -1 : static_cast<std::int64_t>(pair_of.at(PairKey{el.fault, s1, s2})));
          S.tip_neighbours.emplace_back();
        }
        tri[c] = it->second;
      }
      S.mesh.add_element(S.mesh.block(2, ent, ElementType::Triangle), tri, el.tag);
      S.triangles.push_back(tri);
      S.triangle_fault.push_back(static_cast<std::int32_t>(fi));
      for (int c = 0; c < 3; ++c)
        if (S.node_pair[tri[c]] < 0)
          for (int d = 0; d < 3; ++d)
            if (d != c && S.node_pair[tri[d]] >= 0) S.tip_neighbours[tri[c]].push_back(tri[d]);
    }
  }
  for (auto& v : S.tip_neighbours) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  // The surface keeps the mesh's tag of each fault group, so readers of the results (ugs-report)
  // name the faults from the mesh. Every group of the surface is a fault group, whose mesh tags are
  // distinct, so the renaming is one simultaneous map.
  std::map<int, int> mesh_tag;
  for (const auto& pg : S.mesh.physicals)
    if (const PhysicalGroup* g = mesh.find_physical(3, pg.name)) mesh_tag[pg.tag] = g->tag;
  if (mesh_tag.size() == S.mesh.physicals.size()) {
    for (auto& pg : S.mesh.physicals) pg.tag = mesh_tag.at(pg.tag);
    for (auto& e : S.mesh.entities)
      for (int& t : e.physicals) t = mesh_tag.at(t);
  }
  S.mesh.update_entity_bboxes();
  return fm;
}

}  // namespace ugs::contact
