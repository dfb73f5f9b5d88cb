//
// Copyright (c) 2026 ZettaScale Technology
//
// This program and the accompanying materials are made available under the
// terms of the Eclipse Public License 2.0 which is available at
// http://www.eclipse.org/legal/epl-2.0, or the Apache License, Version 2.0
// which is available at https://www.apache.org/licenses/LICENSE-2.0.
//
// SPDX-License-Identifier: EPL-2.0 OR Apache-2.0
//
// Contributors:
//   ZettaScale Zenoh Team, <zenoh@zettascale.tech>
//

#ifndef ZENOH_PICO_COLLECTIONS_CAT_H
#define ZENOH_PICO_COLLECTIONS_CAT_H
#define _ZP_CAT_INNER(a, b) a##_##b
#define _ZP_CAT(a, b) _ZP_CAT_INNER(a, b)

// Forces an extra rescan of `x`.  Needed to work around the traditional
// (non-conforming) MSVC preprocessor, which otherwise treats an expanded
// __VA_ARGS__ as a single argument when it is forwarded to another
// function-like macro.  Compilers with a conforming preprocessor (GCC, Clang,
// MSVC with /Zc:preprocessor) are unaffected by the extra indirection.
#define _ZP_EXPAND(x) x

// Variadic arguments counting, up to 10
#define _ZP_VA_NARGS_IMPL(_1, _2, _3, _4, _5, _6, _7, _8, _9, _10, N, ...) N
#define _ZP_VA_NARGS(...) _ZP_EXPAND(_ZP_VA_NARGS_IMPL(__VA_ARGS__, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1))
#endif
