#pragma once
// TESSERA_CPU_VERSIONS before a hot loop's function (the explicit step's SIMD loops, the implicit
// evaluation's pair): on x86-64 it is compiled for the baseline CPU, AVX2 and AVX-512 (GCC's and
// Clang's target_clones: vector lanes and fused multiply-adds), and the version the CPU runs is
// chosen when the library loads; elsewhere (ARM, other compilers), or with TESSERA_PORTABLE (the
// CMake option, which the sanitizer build sets), the one version for the target.
#if !defined(TESSERA_PORTABLE) && defined(__x86_64__) && defined(__ELF__) && (defined(__GNUC__) || defined(__clang__))
#define TESSERA_CPU_VERSIONS __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define TESSERA_CPU_VERSIONS
#endif

// TESSERA_FLATTEN: every call inside the function inlined into it (GCC's and Clang's flatten), so
// that a function built in CPU versions runs its callees in the same version.
#if defined(__GNUC__) || defined(__clang__)
#define TESSERA_FLATTEN __attribute__((flatten))
#else
#define TESSERA_FLATTEN
#endif
