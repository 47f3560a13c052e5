#include <algorithm>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include "local_mesh.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::mech {
namespace {

constexpr int kTag = 7100;

// A byte buffer of POD arrays, written and read back in the same order.
class Buffer {
public:
  template <class T>
  void put(const std::vector<T>& v) {
    put_value<std::uint64_t>(v.size());
    const auto* p = reinterpret_cast<const char*>(v.data());
    data_.insert(data_.end(), p, p + v.size() * sizeof(T));
  }
  template <class T>
  void put_value(const T& x) {
    const auto* p = reinterpret_cast<const char*>(&x);
    data_.insert(data_.end(), p, p + sizeof(T));
  }
  template <class T>
  std::vector<T> get() {
    const auto n = get_value<std::uint64_t>();
    std::vector<T> v(n);
    std::memcpy(v.data(), data_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  template <class T>
  T get_value() {
    T x;
    std::memcpy(&x, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return x;
  }
  std::vector<char>& bytes() { return data_; }

private:
  std::vector<char> data_;
  std::size_t pos_ = 0;
};

void put_material(Buffer& b, const fem::Material& m) {
  std::vector<char> name(m.name.begin(), m.name.end());
  b.put(name);
  b.put_value(static_cast<int>(m.law));
  b.put_value(m.ratios);
  b.put_value(m.biot);
  b.put_value(m.E_z);
  b.put_value(m.hypo);
  b.put_value(m.Dhat);
  b.put_value(m.D_linear);
}

fem::Material get_material(Buffer& b) {
  fem::Material m;
  const auto name = b.get<char>();
  m.name.assign(name.begin(), name.end());
  m.law = static_cast<fem::Law>(b.get_value<int>());
  m.ratios = b.get_value<fem::TIRatios>();
  m.biot = b.get_value<double>();
  m.E_z = b.get_value<double>();
  m.hypo = b.get_value<fem::HypoParams>();
  m.Dhat = b.get_value<fem::Mat6>();
  m.D_linear = b.get_value<fem::Mat6>();
  return m;
}

// The initial state: its numbers, then its tables (which a POD copy would not carry).
void put_initial(Buffer& b, const InitialState& s) {
  b.put(std::vector<double>{s.surface_elevation, s.lithostatic, s.hydrostatic, s.k_Hmax, s.k_hmin, s.Hmax_azimuth_deg,
                            s.sHmax_over_shmin});
  b.put(s.sv_gradient);
  b.put(s.sv_total);
  b.put(s.shmin);
  b.put(s.sHmax);
  b.put(s.overpressure);
}

InitialState get_initial(Buffer& b) {
  InitialState s;
  const auto v = b.get<double>();
  s.surface_elevation = v[0], s.lithostatic = v[1], s.hydrostatic = v[2], s.k_Hmax = v[3], s.k_hmin = v[4];
  s.Hmax_azimuth_deg = v[5], s.sHmax_over_shmin = v[6];
  s.sv_gradient = b.get<DepthValue>();
  s.sv_total = b.get<double>();
  s.shmin = b.get<DepthValue>();
  s.sHmax = b.get<DepthValue>();
  s.overpressure = b.get<DepthValue>();
  return s;
}

void send_buffer(MPI_Comm comm, Buffer& b, int dest) {
  std::uint64_t n = b.bytes().size();
  MPI_Send(&n, 1, MPI_UINT64_T, dest, kTag, comm);
  send_bytes(comm, b.bytes().data(), n, dest, kTag + 1);
}

Buffer recv_buffer(MPI_Comm comm, int src) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, src, kTag, comm, MPI_STATUS_IGNORE);
  Buffer b;
  b.bytes().resize(n);
  recv_bytes(comm, b.bytes().data(), n, src, kTag + 1);
  return b;
}

}  // namespace

void send_bytes(MPI_Comm comm, const void* data, std::size_t n, int dest, int tag) {
  const char* p = static_cast<const char*>(data);
  constexpr std::size_t chunk = std::size_t(1) << 30;
  for (std::size_t off = 0; off < n || (n == 0 && off == 0); off += chunk) {
    const int len = static_cast<int>(std::min(chunk, n - off));
    MPI_Send(p + off, len, MPI_BYTE, dest, tag, comm);
    if (n == 0) break;
  }
}

void recv_bytes(MPI_Comm comm, void* data, std::size_t n, int src, int tag) {
  char* p = static_cast<char*>(data);
  constexpr std::size_t chunk = std::size_t(1) << 30;
  for (std::size_t off = 0; off < n || (n == 0 && off == 0); off += chunk) {
    const int len = static_cast<int>(std::min(chunk, n - off));
    MPI_Recv(p + off, len, MPI_BYTE, src, tag, comm, MPI_STATUS_IGNORE);
    if (n == 0) break;
  }
}

LocalMesh distribute(MPI_Comm comm, const Model* model, PartitionMethod method) {
  LocalMesh lm;
  lm.comm = comm;
  MPI_Comm_rank(comm, &lm.rank);
  MPI_Comm_size(comm, &lm.size);
  const int P = lm.size;
  std::vector<Buffer> out(P);
  // Rank 0's preparation may fail (partitioner); every rank must learn it.
  collective(comm, [&] {
  if (lm.rank == 0) {
    const Model& m = *model;
    const std::size_t n = m.num_nodes();
    const std::vector<int> part = partition_nodes(m, m.x, P, method);
    // Global numbering: the nodes of part 0 first, each part in mesh order.
    std::vector<std::int64_t> begin(P + 1, 0);
    for (int p : part) ++begin[p + 1];
    for (int p = 0; p < P; ++p) begin[p + 1] += begin[p];
    for (int p = 0; p < P; ++p)
      if (begin[p + 1] == begin[p])
        throw ComputeError("partition left rank " + std::to_string(p) + " without nodes (too many processes for this mesh)");
    std::vector<std::int64_t> global(n);
    lm.orig_of_global.resize(n);
    {
      std::vector<std::int64_t> next(begin.begin(), begin.end() - 1);
      for (std::size_t v = 0; v < n; ++v) {
        global[v] = next[part[v]]++;
        lm.orig_of_global[global[v]] = static_cast<std::uint32_t>(v);
      }
    }
    lm.node_begin_of_rank = begin;
    // Elements: to every part owning one of their nodes; reported by the part of their lowest node.
    std::vector<std::vector<std::uint32_t>> cells_of(P);
    lm.owned_cells_of_rank.assign(P, {});
    for (std::uint32_t e = 0; e < m.tets.size(); ++e) {
      const auto& t = m.tets[e];
      int parts[4], np = 0;
      std::int64_t lowest = global[t[0]];
      int owner = part[t[0]];
      for (auto v : t) {
        const int p = part[v];
        if (std::find(parts, parts + np, p) == parts + np) parts[np++] = p;
        if (global[v] < lowest) lowest = global[v], owner = p;
      }
      for (int i = 1; i < np; ++i)  // insertion sort of at most 4 parts
        for (int j = i; j > 0 && parts[j - 1] > parts[j]; --j) std::swap(parts[j - 1], parts[j]);
      for (int k = 0; k < np; ++k) cells_of[parts[k]].push_back(e);
      lm.owned_cells_of_rank[owner].push_back(e);
    }
    for (int p = 0; p < P; ++p) {
      // Local nodes: owned block, then ghosts by global number.
      const std::int64_t b = begin[p], nown = begin[p + 1] - begin[p];
      std::vector<std::int64_t> ghosts;
      for (auto e : cells_of[p])
        for (auto v : m.tets[e])
          if (part[v] != p) ghosts.push_back(global[v]);
      std::sort(ghosts.begin(), ghosts.end());
      ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
      std::vector<std::int64_t> gl(nown + ghosts.size());
      std::iota(gl.begin(), gl.begin() + nown, b);
      std::copy(ghosts.begin(), ghosts.end(), gl.begin() + nown);
      std::unordered_map<std::int64_t, std::int32_t> ghost_local;
      ghost_local.reserve(ghosts.size() * 2);
      for (std::size_t k = 0; k < ghosts.size(); ++k) ghost_local[ghosts[k]] = static_cast<std::int32_t>(nown + k);
      auto local_of = [&](std::uint32_t v) -> std::int32_t {
        const std::int64_t g = global[v];
        return part[v] == p ? static_cast<std::int32_t>(g - b) : ghost_local.at(g);
      };
      std::vector<std::uint32_t> orig(gl.size());
      std::vector<Point3> x(gl.size());
      std::vector<std::uint8_t> fixed(gl.size());
      std::vector<std::array<double, 3>> pres(gl.size()), trac(gl.size());
      for (std::size_t k = 0; k < gl.size(); ++k) {
        const std::uint32_t v = lm.orig_of_global[gl[k]];
        orig[k] = v;
        x[k] = m.x[v];
        fixed[k] = m.fixed[v];
        pres[k] = m.prescribed[v];
        trac[k] = m.traction_force.empty() ? std::array<double, 3>{0, 0, 0} : m.traction_force[v];
      }
      std::vector<std::array<std::int32_t, 4>> cells(cells_of[p].size());
      std::vector<std::int32_t> mat(cells.size());
      std::vector<std::uint8_t> owned(cells.size(), 0);
      for (std::size_t k = 0; k < cells.size(); ++k) {
        const auto& t = m.tets[cells_of[p][k]];
        cells[k] = {local_of(t[0]), local_of(t[1]), local_of(t[2]), local_of(t[3])};
        mat[k] = m.tet_material[cells_of[p][k]];
      }
      // Mark the owned ones (both lists are in increasing element order).
      {
        const auto& own = lm.owned_cells_of_rank[p];
        std::size_t j = 0;
        for (std::size_t k = 0; k < cells.size() && j < own.size(); ++k)
          if (cells_of[p][k] == own[j]) owned[k] = 1, ++j;
      }
      Buffer& buf = out[p];
      buf.put_value<std::int64_t>(static_cast<std::int64_t>(n));
      buf.put_value<std::int64_t>(static_cast<std::int64_t>(m.tets.size()));
      buf.put_value<std::int64_t>(b);
      buf.put_value<std::int64_t>(nown);
      buf.put(gl);
      buf.put(orig);
      buf.put(x);
      buf.put(fixed);
      buf.put(pres);
      buf.put(trac);
      buf.put(cells);
      buf.put(mat);
      buf.put(cells_of[p]);
      buf.put(owned);
      buf.put_value<std::uint64_t>(m.materials.size());
      for (const auto& mt : m.materials) put_material(buf, mt);
      put_initial(buf, m.initial);
      // (a Model made without build_model may lack the per-material ratios and gas columns: the
      // global ratios and water then)
      buf.put(m.material_k.size() == m.materials.size()
                  ? m.material_k
                  : std::vector<std::array<double, 2>>(m.materials.size(), {m.initial.k_Hmax, m.initial.k_hmin}));
      buf.put(m.material_gas.size() == m.materials.size() ? m.material_gas : std::vector<GasColumn>(m.materials.size()));
      cells_of[p] = {};
    }
  }
  });
  if (lm.rank == 0) {
    for (int p = 1; p < P; ++p) {
      send_buffer(comm, out[p], p);
      out[p] = Buffer();
    }
  }
  Buffer in = lm.rank == 0 ? std::move(out[0]) : recv_buffer(comm, 0);
  lm.n_global_nodes = in.get_value<std::int64_t>();
  lm.n_global_cells = in.get_value<std::int64_t>();
  lm.node_begin = in.get_value<std::int64_t>();
  lm.n_owned = static_cast<int>(in.get_value<std::int64_t>());
  lm.global = in.get<std::int64_t>();
  lm.orig = in.get<std::uint32_t>();
  lm.x = in.get<Point3>();
  lm.fixed = in.get<std::uint8_t>();
  lm.prescribed = in.get<std::array<double, 3>>();
  lm.traction = in.get<std::array<double, 3>>();
  lm.cells = in.get<std::array<std::int32_t, 4>>();
  lm.cell_material = in.get<std::int32_t>();
  lm.cell_index = in.get<std::uint32_t>();
  lm.cell_owned = in.get<std::uint8_t>();
  const auto nm = in.get_value<std::uint64_t>();
  for (std::uint64_t k = 0; k < nm; ++k) lm.materials.push_back(get_material(in));
  lm.initial = get_initial(in);
  lm.material_k = in.get<std::array<double, 2>>();
  lm.material_gas = in.get<GasColumn>();
  return lm;
}

}  // namespace ugs::mech
