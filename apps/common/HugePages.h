#pragma once
// Transparent huge pages for a program's large allocations, where the kernel
// gives them only on request.
//
// A software GL driver (Mesa's llvmpipe) keeps every texture in memory from
// malloc and zeroes it when it is made; the kernel then faults the memory in
// 4 KiB at a time, which on a virtual machine is most of the cost of a first
// frame's targets and peel layers (a 1024 x 768 frame of the Menger sponge:
// 384 MiB of layers). Where /sys/kernel/mm/transparent_hugepage/enabled says
// "madvise", glibc (2.35 and later) asks for huge pages for its large blocks
// when its tunable glibc.malloc.hugetlb=1 is set; tunables are read when a
// program starts, so the program runs itself again, once, with the tunable
// added to GLIBC_TUNABLES.

#include <optional>
#include <string>

namespace strata::apps {

// Whether this process was started with glibc.malloc.hugetlb=1 (for a
// benchmark's record of its conditions).
bool startedWithHugePages();

// GLIBC_TUNABLES with glibc.malloc.hugetlb=1 added to `current` (the
// variable's value, null when unset), given the first line of the kernel's
// transparent_hugepage/enabled; nullopt where runWithHugePages leaves the
// program as it is.
std::optional<std::string> tunablesForHugePages(const char* current, const std::string& hugePageSetting);

// Call first in main, before any thread or file is opened. Returns (doing
// nothing) when GLIBC_TUNABLES already names glibc.malloc.hugetlb (a user's
// glibc.malloc.hugetlb=0 keeps huge pages off), when the kernel gives huge
// pages always or never, in sanitizer builds, with a glibc without the
// tunable, or when the program cannot run itself again; otherwise does not
// return.
void runWithHugePages(char** argv);

}  // namespace strata::apps
