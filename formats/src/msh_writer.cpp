// MSH 4.1 writer. All nodes go in one block on the first entity of the highest dimension, so a
// file we write, read back and write again is byte-identical.
#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "ugs/formats/msh.hpp"

namespace ugs {
namespace {

class MshWriter {
public:
  MshWriter(const Mesh& m, OutputFile& out, bool binary) : m_(m), out_(out), binary_(binary) {}

  void write() {
    put("$MeshFormat\n");
    put(binary_ ? "4.1 1 8\n" : "4.1 0 8\n");
    if (binary_) {
      const int one = 1;
      raw(&one, sizeof one);
      put("\n");
    }
    put("$EndMeshFormat\n");
    write_physical_names();
    write_entities();
    write_nodes();
    write_elements();
    write_provenance();
    flush();
  }

private:
  void put(std::string_view s) { buf_.append(s); if (buf_.size() > (1 << 22)) flush(); }
  void raw(const void* p, std::size_t n) { buf_.append(static_cast<const char*>(p), n); if (buf_.size() > (1 << 22)) flush(); }
  template <class T> void bin(T v) { raw(&v, sizeof v); }
  void flush() { out_.write(buf_); buf_.clear(); }
  template <class... A> void text(fmt::format_string<A...> f, A&&... a) {
    fmt::format_to(std::back_inserter(buf_), f, std::forward<A>(a)...);
    if (buf_.size() > (1 << 22)) flush();
  }
  void size(std::uint64_t v, char sep = ' ') { binary_ ? bin(v) : text("{}{}", v, sep); }
  void integer(int v, char sep = ' ') { binary_ ? bin(v) : text("{}{}", v, sep); }
  void real(double v, char sep = ' ') { binary_ ? bin(v) : text("{}{}", v, sep); }

  void write_physical_names() {
    if (m_.physicals.empty()) return;
    put("$PhysicalNames\n");
    text("{}\n", m_.physicals.size());
    for (const auto& p : m_.physicals) text("{} {} \"{}\"\n", p.dim, p.tag, p.name);
    put("$EndPhysicalNames\n");
  }

  std::vector<const Entity*> entities_of(int dim) const {
    std::vector<const Entity*> r;
    for (const auto& e : m_.entities)
      if (e.dim == dim) r.push_back(&e);
    return r;
  }

  void write_entities() {
    put("$Entities\n");
    for (int d = 0; d < 4; ++d) size(entities_of(d).size(), d == 3 ? '\n' : ' ');
    for (int d = 0; d < 4; ++d)
      for (const Entity* e : entities_of(d)) {
        integer(e->tag);
        for (int k = 0; k < (d == 0 ? 3 : 6); ++k) real(e->bbox[k]);
        size(e->physicals.size());
        for (int p : e->physicals) integer(p);
        if (d > 0) size(0);  // no bounding entities: discrete geometry
        if (!binary_) buf_.back() = '\n';
      }
    if (binary_) put("\n");
    put("$EndEntities\n");
  }

  // The entity holding the nodes: first entity of the highest dimension present.
  std::pair<int, int> node_entity() const {
    std::pair<int, int> best{-1, 0};
    for (const auto& e : m_.entities)
      if (e.dim > best.first) best = {e.dim, e.tag};
    if (best.first < 0) return {0, 0};
    return best;
  }

  void write_nodes() {
    const std::size_t n = m_.num_nodes();
    std::uint64_t lo = n ? *std::min_element(m_.node_tags.begin(), m_.node_tags.end()) : 0;
    std::uint64_t hi = n ? *std::max_element(m_.node_tags.begin(), m_.node_tags.end()) : 0;
    put("$Nodes\n");
    const std::uint64_t nblocks = n ? 1 : 0;
    size(nblocks);
    size(n);
    size(lo);
    size(hi, '\n');
    if (n) {
      auto [edim, etag] = node_entity();
      integer(edim);
      integer(etag);
      integer(0);
      size(n, '\n');
      if (binary_) {
        raw(m_.node_tags.data(), n * sizeof(std::uint64_t));
        static_assert(sizeof(Point3) == 3 * sizeof(double));  // the coordinates are one array: one append
        raw(m_.nodes.data(), n * sizeof(Point3));
      } else {
        for (auto t : m_.node_tags) text("{}\n", t);
        for (const auto& x : m_.nodes) text("{} {} {}\n", x[0], x[1], x[2]);
      }
    }
    if (binary_) put("\n");
    put("$EndNodes\n");
  }

  void write_elements() {
    std::uint64_t total = 0, lo = ~0ull, hi = 0;
    for (const auto& b : m_.blocks) {
      total += b.size();
      for (auto t : b.tags) lo = std::min(lo, t), hi = std::max(hi, t);
    }
    if (total == 0) lo = 0;
    std::uint64_t nblocks = 0;
    for (const auto& b : m_.blocks) nblocks += b.size() > 0;
    put("$Elements\n");
    size(nblocks);
    size(total);
    size(lo);
    size(hi, '\n');
    std::vector<std::uint64_t> rec;
    for (const auto& b : m_.blocks) {
      if (b.size() == 0) continue;
      integer(b.entity_dim);
      integer(b.entity_tag);
      integer(static_cast<int>(b.type));
      size(b.size(), '\n');
      const int npe = b.npe();
      if (binary_) {
        // Records written straight into the buffer, a few MB at a time (an append per element
        // was most of the writing time of millions of tetrahedra).
        const std::size_t words = 1 + static_cast<std::size_t>(npe);
        const std::size_t per_chunk = std::max<std::size_t>(1, (std::size_t{1} << 22) / (words * sizeof(std::uint64_t)));
        for (std::size_t i0 = 0; i0 < b.size(); i0 += per_chunk) {
          const std::size_t i1 = std::min(b.size(), i0 + per_chunk);
          rec.resize(words * (i1 - i0));
          std::uint64_t* r = rec.data();
          for (std::size_t i = i0; i < i1; ++i) {
            *r++ = b.tags[i];
            for (int k = 0; k < npe; ++k) *r++ = m_.node_tags[b.nodes[i * npe + k]];
          }
          raw(rec.data(), rec.size() * sizeof(std::uint64_t));
        }
      } else {
        for (std::size_t i = 0; i < b.size(); ++i) {
          text("{}", b.tags[i]);
          for (int k = 0; k < npe; ++k) text(" {}", m_.node_tags[b.nodes[i * npe + k]]);
          put("\n");
        }
      }
    }
    if (binary_) put("\n");
    put("$EndElements\n");
  }

  void write_provenance() {
    if (m_.provenance.empty()) return;
    put("$UgsProvenance\n");
    text("{}\n", m_.provenance.size());
    for (const auto& l : m_.provenance) {
      std::string s = l;
      std::replace(s.begin(), s.end(), '\n', ' ');
      text("{}\n", s);
    }
    put("$EndUgsProvenance\n");
  }

  const Mesh& m_;
  OutputFile& out_;
  bool binary_;
  std::string buf_;
};

}  // namespace

void write_msh(const Mesh& mesh, OutputFile& out, MshEncoding enc) {
  MshWriter(mesh, out, enc == MshEncoding::Binary).write();
}

void write_msh(const Mesh& mesh, const std::string& path, MshEncoding enc) {
  OutputFile out(path);
  write_msh(mesh, out, enc);
  out.commit();
}

}  // namespace ugs
