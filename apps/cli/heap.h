// The process heap for large inputs (issue #24, item 8: whole-process speed).
#pragma once
#include <cstddef>

namespace interfere::cli {

/// Prepares the heap for a command that will allocate about `bytes` (a hint: the inputs' sizes
/// times a few): every block then comes from the one heap and freed blocks are reused instead of
/// returned to the system (the process is short-lived), and the first `bytes` of the heap are
/// advised to the kernel as transparent huge pages. A fresh process otherwise spends much of its
/// time in first-touch page faults (one per 4 KiB page of every new buffer: the file bytes, the
/// weld's scratch, the mesh, the trees). Only the first call acts; below 64 MiB it does nothing.
/// Changes no result, only where the memory comes from.
void prepare_heap(std::size_t bytes);

}  // namespace interfere::cli
