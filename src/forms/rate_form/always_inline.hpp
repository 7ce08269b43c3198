#pragma once
/// \file always_inline.hpp
/// Internal to src/forms: SPHSTAB_ALWAYS_INLINE, for the rate form's per-pair terms and loop bodies, which GCC would
/// otherwise call out of line from the row loops (measured: 35-50 % slower rates).
#if defined(__GNUC__)
#define SPHSTAB_ALWAYS_INLINE __attribute__((always_inline))
#else
#define SPHSTAB_ALWAYS_INLINE
#endif
