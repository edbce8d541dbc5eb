// CAD runs in a second executable (issue #24, item 8). OpenCASCADE and its ~45 shared libraries
// took ~45 ms of dynamic loading at every start of `interfere`, mesh-only runs included. So the CLI
// is built twice from the same sources: `interfere` without OCCT, and `interfere-cad` with it
// (build tree: beside `interfere`; installed: <libexecdir>/interfere/). Where a run needs OCCT (a
// STEP input, `features`, `assembly-clash`), `interfere` hands it over, same arguments, before it
// has written anything; `interfere-cad` simply continues. Without OCCT in the build there is one
// executable and such runs are an input error.
#pragma once
#include <string>
#include <vector>

namespace interfere::cli {

/// main() keeps argv for require_cad (it must outlive the call: argv itself does).
void remember_arguments(char** argv);

/// Called where a run needs OpenCASCADE, before anything is written; `what` names it ("STEP input
/// B.step", "`interfere features`"). interfere-cad: returns. interfere: replaces this process with
/// interfere-cad (execv, the same arguments, so reports show the same command line; unless the user
/// set GLIBC_TUNABLES, its environment gets glibc malloc settings for it, cad_exec.cpp); throws
/// InputError naming the executable's paths when it is missing or cannot run. A build without
/// OCCT: throws InputError "<what> needs interfere built with OpenCASCADE (INTERFERE_WITH_OCCT)".
void require_cad(const std::string& what);

/// interfere-cad, installed (<libexecdir>/interfere/): when INTERFERE_DATA_DIR is unset, points it
/// at the install's share/interfere found relative to this executable, so that a relocated tree
/// (a .deb under /usr, an unpacked package) reads its own feature data, not the configured
/// prefix's. Elsewhere (the build tree, `interfere`): does nothing.
void use_installed_data_dir();

/// require_cad for every STEP file among `files`.
void require_cad_for_step_files(const std::vector<std::string>& files);

}  // namespace interfere::cli
