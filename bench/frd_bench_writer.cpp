// Bench-only CalculiX .frd writer (issue #26, item 7); layouts in frd_bench_writer.h.
#include "frd_bench_writer.h"

#include <cerrno>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

namespace interfere::bench_frd {
namespace {

int frd_type(ElemType t) {
  switch (t) {
    case ElemType::hex8: return 1;
    case ElemType::wedge6: return 2;
    case ElemType::tet4: return 3;
    default: return 0;
  }
}

/// Buffered output to a FILE (appends to a string, flushed by the MB).
class Out {
 public:
  explicit Out(std::FILE* f) : f_(f) { buf_.reserve(kChunk + 4096); }
  ~Out() { flush(); }
  void text(const char* s, std::size_t n) {
    buf_.append(s, n);
    maybe_flush();
  }
  void line(const char* fmt, ...) __attribute__((format(printf, 2, 3))) {
    char b[512];
    va_list ap;
    va_start(ap, fmt);
    const int n = std::vsnprintf(b, sizeof b, fmt, ap);
    va_end(ap);
    buf_.append(b, static_cast<std::size_t>(n));
    buf_ += '\n';
    maybe_flush();
  }
  template <class T>
  void raw(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    buf_.append(b, sizeof(T));
    maybe_flush();
  }
  bool flush() {
    if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size()) ok_ = false;
    buf_.clear();
    return ok_;
  }
  bool ok() const { return ok_; }

 private:
  static constexpr std::size_t kChunk = 1 << 20;
  void maybe_flush() {
    if (buf_.size() >= kChunk) flush();
  }
  std::FILE* f_;
  std::string buf_;
  bool ok_ = true;
};

/// A header record of 2C/3C: "    2C" + 18 blanks + count I12 + 37 blanks + format I1.
void block_header(Out& o, const char* key, std::size_t count, int format) {
  o.line("%5s%1s%18s%12zu%37s%1d", key, "C", "", count, "", format);
}

}  // namespace

Status write_frd(const FemMesh& m, const NodalSeries* disp, const std::filesystem::path& path,
                 const FrdWriteOptions& options) {
  const std::string name = path.string();
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    if (frd_type(m.elem_types[e]) == 0) {
      return Error{.file = name, .reason = std::string("bench frd writer: element type ") + elem_info(m.elem_types[e]).name +
                                           " not supported (tet4, wedge6, hex8)"};
    }
  }
  if (disp) {
    for (const auto& v : disp->values) {
      if (v.size() != m.num_nodes()) return Error{.file = name, .reason = "bench frd writer: a step without one value per node"};
    }
  }
  const std::filesystem::path tmp = path.string() + ".tmp";
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(tmp.c_str(), "wb"), &std::fclose);
  if (!f) return Error{.file = tmp.string(), .reason = std::string("cannot open: ") + std::strerror(errno)};
  const bool bin = options.binary;
  {
    Out o(f.get());
    o.line("    1C");
    o.line("    1U%-66s", options.title.c_str());
    o.line("    1UUSER");
    o.line("    1UPGM               CalculiX");
    o.line("    1UVERSION           Version 2.20");
    for (std::size_t g = 0; g < m.groups.size(); ++g) o.line("    1UMAT%5zu%-66s", g + 1, m.groups[g].name.c_str());
    if (m.groups.empty()) o.line("    1UMAT%5d%-66s", 1, "MATERIAL");

    block_header(o, "2", m.num_nodes(), bin ? 3 : 1);
    for (std::size_t i = 0; i < m.num_nodes(); ++i) {
      const Vec3& x = m.nodes[i];
      if (bin) {
        o.raw(static_cast<std::int32_t>(m.node_ids[i]));
        o.raw(x.x), o.raw(x.y), o.raw(x.z);
      } else {
        o.line(" -1%10lld%12.5E%12.5E%12.5E", static_cast<long long>(m.node_ids[i]), x.x, x.y, x.z);
      }
    }
    if (!bin) o.line(" -3");

    block_header(o, "3", m.num_elements(), bin ? 2 : 1);
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      const int type = frd_type(m.elem_types[e]);
      const int mat = m.elem_groups[e] >= 0 ? m.elem_groups[e] + 1 : 1;
      const std::uint32_t* v = m.element_nodes(e);
      const int n = m.element_size(e);
      if (bin) {
        for (std::int64_t x : {m.elem_ids[e], std::int64_t{type}, std::int64_t{0}, std::int64_t{mat}}) o.raw(static_cast<std::int32_t>(x));
        for (int q = 0; q < n; ++q) o.raw(static_cast<std::int32_t>(m.node_ids[v[q]]));
      } else {
        o.line(" -1%10lld%5d%5d%5d", static_cast<long long>(m.elem_ids[e]), type, 0, mat);
        char b[16 * 11 + 8];
        std::size_t len = 0;
        for (int q = 0; q < n; ++q) {
          if (q % 10 == 0) {
            if (q) {
              b[len++] = '\n';
              o.text(b, len);
              len = 0;
            }
            std::memcpy(b, " -2", 3);
            len = 3;
          }
          len += static_cast<std::size_t>(std::snprintf(b + len, sizeof b - len, "%10lld", static_cast<long long>(m.node_ids[v[q]])));
        }
        b[len++] = '\n';
        o.text(b, len);
      }
    }
    if (!bin) o.line(" -3");

    if (disp) {
      for (std::size_t s = 0; s < disp->values.size(); ++s) {
        const double t = s < disp->times.size() ? disp->times[s] : static_cast<double>(s + 1);
        o.line("    1PSTEP%26zu%12zu%12d", s + 1, s + 1, 1);
        // (1X,' 100','C',6A1,E12.5,I12,20A1,I2,I5,10A1,I2)
        o.line("  100CL%5zu%12.5E%12zu%20s%2d%5zu%10s%2d", 101 + s, t, m.num_nodes(), "", 0, s + 1, "", bin ? 2 : 1);
        o.line(" -4  DISP        4    1");
        o.line(" -5  D1          1    2    1    0");
        o.line(" -5  D2          1    2    2    0");
        o.line(" -5  D3          1    2    3    0");
        o.line(" -5  ALL         1    2    0    0    1ALL");
        const std::vector<Vec3>& u = disp->values[s];
        for (std::size_t i = 0; i < m.num_nodes(); ++i) {
          if (bin) {
            o.raw(static_cast<std::int32_t>(m.node_ids[i]));
            o.raw(static_cast<float>(u[i].x)), o.raw(static_cast<float>(u[i].y)), o.raw(static_cast<float>(u[i].z));
          } else {
            o.line(" -1%10lld%12.5E%12.5E%12.5E", static_cast<long long>(m.node_ids[i]), u[i].x, u[i].y, u[i].z);
          }
        }
        if (!bin) o.line(" -3");
      }
    }
    o.line(" 9999");
    if (!o.flush()) return Error{.file = tmp.string(), .reason = "write failed (disk full?)"};
  }
  if (std::fclose(f.release()) != 0) return Error{.file = tmp.string(), .reason = "write failed on close"};
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) return Error{.file = name, .reason = "cannot rename " + tmp.string() + ": " + ec.message()};
  return {};
}

}  // namespace interfere::bench_frd
