// Exodus II reader (issue #26, item 1) through the Exodus II library (Sandia's SEACAS exodusII C
// API, Debian libexodusii-dev, on netCDF): no hand-written netCDF reading. Built when CMake finds
// the library (INTERFERE_WITH_EXODUS); otherwise read_fem answers "this build has no Exodus II
// reader". Reads (Exodus II API manual, Schoof & Yarberry, SAND92-2137):
//
// - coordinates (ex_get_coord; 2-D files get z = 0) and the node / element number maps
//   (ex_get_id_map: the solver's ids; 1..n when the file has none);
// - element blocks (ex_get_ids, ex_get_block, ex_get_conn): one group per block, named by the
//   block's name (ex_get_names) else "block <id>", id = the block id. Types by Exodus name prefix
//   and node count: HEX 8/20, TET/TETRA 4/10, WEDGE 6/15, PYRAMID 5/13, TRI/TRIANGLE/TRISHELL 3/6,
//   QUAD/SHELL 4/8/9, BAR/BEAM/TRUSS/ROD 2/3, SPHERE/CIRCLE 1. Exodus HEX20 and WEDGE15 list the
//   mid-side nodes bottom, vertical, top (Nastran's order): converted to VTK's (nastran_to_vtk);
//   TETRA10, PYRAMID13 and QUAD8/9 already use VTK's order. HEX27 (face and body nodes in another
//   order) and polyhedra are errors naming the block;
// - nodal displacements of every time step (ex_get_all_times, ex_get_nodal_var): the nodal
//   variables <base>_X/_Y/_Z or <base>X/Y/Z whose base contains "disp" (any case: DISPL_X, DISP_X,
//   displacement_x ...) form one NodalSeries named by the base. More than one such base, or an
//   incomplete triple, is an error; a file with time steps and nodal variables but no
//   displacements too (a results file the clash check cannot deform). A mesh-only file (no nodal
//   variables) is read without fields.
//
// The library is not linked: it is opened with dlopen at the first Exodus read (exodus_api below),
// because linking it loads libexoIIv2c, netCDF, HDF5 and MPI into every process that links
// interfere_fem, ~46 ms at every start of the `interfere` tool (issue #24's whole-process times).
// exodusII.h still gives the types, constants and, through decltype, each function's exact type.
#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <mutex>

#include "scan.h"

#ifdef INTERFERE_WITH_EXODUS
#include <dlfcn.h>
#include <exodusII.h>

#include <type_traits>
#endif

namespace interfere {

bool fem_has_exodus_reader() {
#ifdef INTERFERE_WITH_EXODUS
  return true;
#else
  return false;
#endif
}

namespace fem_io {

#ifndef INTERFERE_WITH_EXODUS

Expected<FemMesh> read_exodus(const std::filesystem::path& path) {
  return file_error(path.string(), "this build has no Exodus II reader (configure with the Exodus II library: Debian libexodusii-dev)");
}

#else

namespace {

bool exodus_type(std::string_view name, int nodes, ElemType& t) {
  const std::string n = to_lower(name);
  auto is = [&](std::initializer_list<const char*> prefixes) {
    for (const char* p : prefixes) {
      if (n.starts_with(p)) return true;
    }
    return false;
  };
  struct Opt {
    int nodes;
    ElemType type;
  };
  auto pick = [&](std::initializer_list<Opt> opts) {
    for (const Opt& o : opts) {
      if (o.nodes == nodes) {
        t = o.type;
        return true;
      }
    }
    return false;
  };
  if (is({"hex"})) return pick({{8, ElemType::hex8}, {20, ElemType::hex20}});
  if (is({"tet"})) return pick({{4, ElemType::tet4}, {10, ElemType::tet10}});
  if (is({"wedge"})) return pick({{6, ElemType::wedge6}, {15, ElemType::wedge15}});
  if (is({"pyra"})) return pick({{5, ElemType::pyr5}, {13, ElemType::pyr13}});
  if (is({"tri"})) return pick({{3, ElemType::tri3}, {6, ElemType::tri6}});
  if (is({"quad", "shell"})) return pick({{4, ElemType::quad4}, {8, ElemType::quad8}, {9, ElemType::quad9}});
  if (is({"bar", "beam", "truss", "rod"})) return pick({{2, ElemType::line2}, {3, ElemType::line3}});
  if (is({"sphere", "circle", "point"})) return pick({{1, ElemType::point1}});
  return false;
}

// Where dlopen looks for the library: its soname (CMake reads it from the library found at
// configure time), then that file's full path (a library outside the loader's search path).
#ifndef INTERFERE_EXODUS_SONAME
#define INTERFERE_EXODUS_SONAME "libexoIIv2c.so"
#endif
#ifndef INTERFERE_EXODUS_PATH
#define INTERFERE_EXODUS_PATH INTERFERE_EXODUS_SONAME
#endif

/// The Exodus II functions the reader calls, resolved from the library once (exodus_api).
/// Each pointer has the type of the function declared in exodusII.h.
struct ExoApi {
  decltype(&ex_opts) opts = nullptr;
  decltype(&ex_open_int) open_int = nullptr;  // ex_open is a macro over ex_open_int
  decltype(&ex_close) close = nullptr;
  decltype(&ex_set_max_name_length) set_max_name_length = nullptr;
  decltype(&ex_get_init) get_init = nullptr;
  decltype(&ex_get_coord) get_coord = nullptr;
  decltype(&ex_get_id_map) get_id_map = nullptr;
  decltype(&ex_get_ids) get_ids = nullptr;
  decltype(&ex_get_names) get_names = nullptr;
  decltype(&ex_get_block) get_block = nullptr;
  decltype(&ex_get_conn) get_conn = nullptr;
  decltype(&ex_get_variable_param) get_variable_param = nullptr;
  decltype(&ex_get_variable_names) get_variable_names = nullptr;
  decltype(&ex_inquire_int) inquire_int = nullptr;
  decltype(&ex_get_all_times) get_all_times = nullptr;
  decltype(&ex_get_nodal_var) get_nodal_var = nullptr;
  std::string error;  ///< why the library or one of its functions could not be loaded; empty when all are
};

ExoApi load_exodus_api() {
  ExoApi a;
  void* lib = nullptr;
  for (const char* name : {INTERFERE_EXODUS_SONAME, INTERFERE_EXODUS_PATH}) {
    lib = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (lib != nullptr) break;
    const char* why = dlerror();
    const std::string msg = why != nullptr ? why : std::string(name) + ": cannot be opened";
    if (a.error.find(msg) == std::string::npos) a.error += (a.error.empty() ? "" : "; ") + msg;  // (same name twice: once)
  }
  if (lib == nullptr) return a;
  a.error.clear();
  // (never closed: the functions stay valid for the rest of the process)
  auto resolve = [&](auto& fn, const char* name) {
    dlerror();
    void* p = dlsym(lib, name);
    if (p == nullptr) {
      const char* why = dlerror();
      if (a.error.empty()) a.error = why ? why : std::string(name) + ": symbol not found";
      return;
    }
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(p);
  };
  resolve(a.opts, "ex_opts");
  resolve(a.open_int, "ex_open_int");
  resolve(a.close, "ex_close");
  resolve(a.set_max_name_length, "ex_set_max_name_length");
  resolve(a.get_init, "ex_get_init");
  resolve(a.get_coord, "ex_get_coord");
  resolve(a.get_id_map, "ex_get_id_map");
  resolve(a.get_ids, "ex_get_ids");
  resolve(a.get_names, "ex_get_names");
  resolve(a.get_block, "ex_get_block");
  resolve(a.get_conn, "ex_get_conn");
  resolve(a.get_variable_param, "ex_get_variable_param");
  resolve(a.get_variable_names, "ex_get_variable_names");
  resolve(a.inquire_int, "ex_inquire_int");
  resolve(a.get_all_times, "ex_get_all_times");
  resolve(a.get_nodal_var, "ex_get_nodal_var");
  return a;
}

/// The library's functions, loaded at the first call (thread-safe: a function-local static).
const ExoApi& exodus_api() {
  static const ExoApi api = load_exodus_api();
  return api;
}

/// Closes the file on every path.
struct ExoFile {
  const ExoApi& ex;
  int id = -1;
  ~ExoFile() {
    if (id >= 0) ex.close(id);
  }
};

/// "DISPL_X" -> ("displ", 0); false unless the name ends in x/y/z after an optional '_' and its
/// base contains "disp".
bool disp_component(const std::string& name, std::string& base, int& comp) {
  std::string n = to_lower(trim(name));
  if (n.size() < 2) return false;
  const char c = n.back();
  if (c < 'x' || c > 'z') return false;
  comp = c - 'x';
  n.pop_back();
  if (!n.empty() && n.back() == '_') n.pop_back();
  if (n.find("disp") == std::string::npos) return false;
  base = std::string(trim(name)).substr(0, n.size());
  return true;
}

}  // namespace

Expected<FemMesh> read_exodus(const std::filesystem::path& path) {
  const std::string file = path.string();
  {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return file_error(file, "cannot open: no such file");
    if (std::filesystem::is_directory(path, ec)) return file_error(file, "cannot open: is a directory");
  }
  const ExoApi& ex = exodus_api();
  if (!ex.error.empty()) return file_error(file, "cannot read: the Exodus II library (libexodusii) could not be loaded: " + ex.error);
  // One Exodus read at a time: netCDF and HDF5 (Debian's builds) are not thread-safe, and callers
  // read two files concurrently (the CLI's two parts, issue #24 item 8: `distance a.e b.e` failed
  // with "netcdf library that does not support netcdf-4" from HDF5's own state). Held until the
  // file is closed (declared before `f`).
  static std::mutex library_mutex;
  const std::lock_guard<std::mutex> lock(library_mutex);
  ex.opts(EX_DEFAULT);  // no messages on stderr, never abort: errors come back as values
  int comp_ws = 8, io_ws = 0;
  float version = 0;
  ExoFile f{ex};
  f.id = ex.open_int(file.c_str(), EX_READ, &comp_ws, &io_ws, &version, EX_API_VERS_NODOT);  // = ex_open(...)
  if (f.id < 0) return file_error(file, "cannot open as an Exodus II file (not netCDF, or not Exodus)");
  ex.set_max_name_length(f.id, 255);
  auto fail = [&](std::string what) { return file_error(file, "Exodus II: " + std::move(what)); };

  char title[MAX_LINE_LENGTH + 1] = {};
  int num_dim = 0, num_nodes = 0, num_elem = 0, num_blk = 0, num_ns = 0, num_ss = 0;
  if (ex.get_init(f.id, title, &num_dim, &num_nodes, &num_elem, &num_blk, &num_ns, &num_ss) < 0)
    return fail("cannot read the file's sizes (ex_get_init)");
  if (num_nodes <= 0) return fail("no nodes");
  if (num_blk <= 0 || num_elem <= 0) return fail("no element blocks");
  if (num_dim < 1 || num_dim > 3) return fail("num_dim = " + std::to_string(num_dim));

  FemMesh m;
  m.file = file;
  const auto nn = static_cast<std::size_t>(num_nodes);
  std::vector<double> x(nn, 0.0), y(nn, 0.0), z(nn, 0.0);
  if (ex.get_coord(f.id, x.data(), num_dim > 1 ? y.data() : nullptr, num_dim > 2 ? z.data() : nullptr) != 0)
    return fail("cannot read the coordinates (ex_get_coord: coordx/coordy/coordz, or coord when file_size is 0)");
  std::vector<int> node_map(nn), elem_map(static_cast<std::size_t>(num_elem));
  if (ex.get_id_map(f.id, EX_NODE_MAP, node_map.data()) < 0) return fail("cannot read the node number map");
  if (ex.get_id_map(f.id, EX_ELEM_MAP, elem_map.data()) < 0) return fail("cannot read the element number map");
  m.nodes.resize(nn);
  m.node_ids.resize(nn);
  for (std::size_t i = 0; i < nn; ++i) {
    m.nodes[i] = Vec3{x[i], y[i], z[i]};
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !std::isfinite(z[i]))
      return fail("node " + std::to_string(node_map[i]) + ": non-finite coordinate");
    m.node_ids[i] = node_map[i];
  }
  if (const std::int64_t d = find_duplicate(m.node_ids); d >= 0)
    return fail("duplicate node id " + std::to_string(m.node_ids[static_cast<std::size_t>(d)]) + " in the node number map");

  // Element blocks.
  std::vector<int> blk_ids(static_cast<std::size_t>(num_blk));
  if (ex.get_ids(f.id, EX_ELEM_BLOCK, blk_ids.data()) < 0) return fail("cannot read the element block ids");
  std::vector<std::vector<char>> name_buf(static_cast<std::size_t>(num_blk), std::vector<char>(256, 0));
  std::vector<char*> names(static_cast<std::size_t>(num_blk));
  for (std::size_t b = 0; b < names.size(); ++b) names[b] = name_buf[b].data();
  if (ex.get_names(f.id, EX_ELEM_BLOCK, names.data()) < 0) {
    for (auto& nb : name_buf) nb.assign(256, 0);  // (names are optional)
  }
  std::size_t e_index = 0;
  std::vector<int> conn;
  std::uint32_t v[32];
  for (std::size_t b = 0; b < blk_ids.size(); ++b) {
    char type[MAX_STR_LENGTH + 1] = {};
    int count = 0, per = 0, edges = 0, faces = 0, attrs = 0;
    const std::string bname = std::string(trim(std::string_view(names[b])));
    const std::string what = "element block " + std::to_string(blk_ids[b]) + (bname.empty() ? "" : " ('" + one_line_name(bname) + "')");
    if (ex.get_block(f.id, EX_ELEM_BLOCK, blk_ids[b], type, &count, &per, &edges, &faces, &attrs) < 0)
      return fail(what + ": cannot read its parameters");
    if (count == 0) continue;
    ElemType et{};
    if (!exodus_type(type, per, et))
      return fail(what + ": unsupported element type " + quote_tok(type) + " with " + std::to_string(per) + " nodes");
    if (count < 0 || e_index + static_cast<std::size_t>(count) > elem_map.size()) return fail(what + ": more elements than the file's total");
    conn.assign(static_cast<std::size_t>(count) * static_cast<std::size_t>(per), 0);
    if (ex.get_conn(f.id, EX_ELEM_BLOCK, blk_ids[b], conn.data(), nullptr, nullptr) < 0) return fail(what + ": cannot read its connectivity");
    const auto g = static_cast<std::int32_t>(m.groups.size());
    m.groups.push_back(FemGroup{.name = bname.empty() ? "block " + std::to_string(blk_ids[b]) : bname, .id = blk_ids[b], .dim = elem_info(et).dim});
    for (int e = 0; e < count; ++e, ++e_index) {
      for (int q = 0; q < per; ++q) {
        const int local = conn[static_cast<std::size_t>(e) * static_cast<std::size_t>(per) + static_cast<std::size_t>(q)];
        if (local < 1 || local > num_nodes)
          return fail(what + ", element " + std::to_string(elem_map[e_index]) + ": node index " + std::to_string(local) + " out of range 1.." + std::to_string(num_nodes));
        v[q] = static_cast<std::uint32_t>(local - 1);
      }
      permute(nastran_to_vtk(et), v, per);
      m.add_element(et, elem_map[e_index], g, v, per);
    }
  }
  if (Status st = check_element_ids(m, {}, false); !st) return fail(st.error().reason + " in the element number map");
  // Group names must be unique (validate_fem_mesh): a repeated block name gets its id appended.
  {
    std::map<std::string, int> seen;
    for (const FemGroup& grp : m.groups) ++seen[grp.name];
    for (FemGroup& grp : m.groups) {
      if (seen[grp.name] > 1) grp.name += " (block " + std::to_string(grp.id) + ")";
    }
  }
  drop_lower_dimension(m, nullptr);
  {
    int top = 0;
    for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
    for (FemGroup& grp : m.groups) grp.dim = top;
  }

  // Nodal displacements of every time step.
  int nvars = 0;
  if (ex.get_variable_param(f.id, EX_NODAL, &nvars) < 0) return fail("cannot read the nodal variable count");
  const auto nsteps = static_cast<int>(ex.inquire_int(f.id, EX_INQ_TIME));
  if (nvars > 0) {
    std::vector<std::vector<char>> vbuf(static_cast<std::size_t>(nvars), std::vector<char>(256, 0));
    std::vector<char*> vnames(static_cast<std::size_t>(nvars));
    for (std::size_t i = 0; i < vnames.size(); ++i) vnames[i] = vbuf[i].data();
    if (ex.get_variable_names(f.id, EX_NODAL, nvars, vnames.data()) < 0) return fail("cannot read the nodal variable names");
    std::map<std::string, std::array<int, 3>> bases;  // base -> 1-based variable index per component
    std::string all;
    for (int i = 0; i < nvars; ++i) {
      const std::string nm(vnames[static_cast<std::size_t>(i)]);
      all += (all.empty() ? "" : ", ") + one_line_name(nm);
      std::string base;
      int comp = 0;
      if (!disp_component(nm, base, comp)) continue;
      auto& slot = bases.try_emplace(base, std::array<int, 3>{0, 0, 0}).first->second;
      if (slot[static_cast<std::size_t>(comp)] != 0) return fail("nodal variable " + quote_tok(nm) + " repeats a displacement component");
      slot[static_cast<std::size_t>(comp)] = i + 1;
    }
    if (bases.empty()) {
      if (nsteps > 0)
        return fail("no displacement among the nodal variables (" + all + "): expected DISPL_X/Y/Z, DISP_X/Y/Z or another <disp...>_X/Y/Z triple");
    } else {
      if (bases.size() > 1) {
        std::string list;
        for (const auto& [b, s] : bases) list += (list.empty() ? "" : ", ") + one_line_name(b);
        return fail("several displacement variables (" + list + "): one is supported");
      }
      const auto& [base, idx] = *bases.begin();
      for (int c = 0; c < 3; ++c) {
        if (idx[static_cast<std::size_t>(c)] == 0)
          return fail("displacement " + one_line_name(base) + ": component " + "XYZ"[c] + " missing (nodal variables: " + all + ")");
      }
      if (nsteps <= 0) return fail("displacement " + one_line_name(base) + " without time steps");
      NodalSeries s{.name = base};
      s.times.resize(static_cast<std::size_t>(nsteps));
      if (ex.get_all_times(f.id, s.times.data()) < 0) return fail("cannot read the time values");
      std::vector<double> comp(nn);
      s.values.assign(static_cast<std::size_t>(nsteps), std::vector<Vec3>(nn));
      for (int st = 0; st < nsteps; ++st) {
        if (!std::isfinite(s.times[static_cast<std::size_t>(st)])) return fail("time step " + std::to_string(st + 1) + ": non-finite time");
        for (int c = 0; c < 3; ++c) {
          // (A warning is an error here: the library then returns no values. It happens when the
          // file's layout flag, the global attribute file_size, disagrees with how its nodal
          // variables are stored: meshio 5 writes vals_nod_var<k> without file_size = 1.)
          if (ex.get_nodal_var(f.id, st + 1, idx[static_cast<std::size_t>(c)], num_nodes, comp.data()) != 0)
            return fail("time step " + std::to_string(st + 1) + ": cannot read " + one_line_name(base) + " component " + "XYZ"[c] +
                        " (the Exodus library finds no values: one array per variable, vals_nod_var<k>, needs the global attribute file_size = 1)");
          for (std::size_t i = 0; i < nn; ++i) {
            if (!std::isfinite(comp[i]))
              return fail("time step " + std::to_string(st + 1) + ", node " + std::to_string(m.node_ids[i]) + ": non-finite " + one_line_name(base) + " component " + "XYZ"[c]);
            s.values[static_cast<std::size_t>(st)][i][c] = comp[i];
          }
        }
      }
      m.fields.push_back(std::move(s));
    }
  }
  return m;
}

#endif

}  // namespace fem_io
}  // namespace interfere
