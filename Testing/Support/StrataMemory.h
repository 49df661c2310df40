// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Memory figures for the leak tests (TestGraphicsResources, TestPagingSoak): the resident set
// and the bytes the allocator has handed out and not had back. Under AddressSanitizer the
// allocator is ASan's (mallinfo2 sees none of it) and its quarantine keeps freed blocks
// resident (up to quarantine_size_mb, 256 MB), so the resident set climbs without a leak: the
// tests then assert the heap, which ASan counts exactly.
#ifndef StrataMemory_h
#define StrataMemory_h

namespace strata_test
{
/// VmRSS of this process in KiB (-1 if /proc is unreadable).
double ResidentKiB();
/// Bytes in use on the heap in KiB: mallinfo2 over all arenas (mmapped blocks too), or ASan's
/// own count in an ASan build.
double HeapInUseKiB();
/// Whether this build runs under AddressSanitizer.
bool UnderAddressSanitizer();
}

#endif
