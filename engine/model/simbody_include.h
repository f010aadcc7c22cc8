// PRIVATE to engine/model: the one way to include Simbody. Debian builds libSimTK* without
// NDEBUG, and some Simbody classes (SimTK::CacheEntryInfo in StateImpl.h) have members only
// when NDEBUG is not defined. Inline Simbody code compiled here with NDEBUG (our release builds)
// would then disagree with the library about those layouts, and the dynamic linker lets the
// library call our copies of the inline functions: a crash in State::updU()/updQ(). So the
// Simbody headers are read with NDEBUG undefined, as the library was built, and NDEBUG is
// restored for the rest of the file.
#pragma once

#ifdef NDEBUG
#define HITL_SIMBODY_RESTORE_NDEBUG
#undef NDEBUG
#endif

#include <Simbody.h>

#ifdef HITL_SIMBODY_RESTORE_NDEBUG
#define NDEBUG
#undef HITL_SIMBODY_RESTORE_NDEBUG
#include <cassert>  // assert() back to what NDEBUG says
#endif
