//
// Copyright (c) 2022 ZettaScale Technology
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

// ⚠️ This file is auto-generated from include/zenoh-pico.h.in

#ifndef ZENOH_PICO_H
#define ZENOH_PICO_H

#define ZENOH_PICO "1.9.0"
#define ZENOH_PICO_MAJOR 1
#define ZENOH_PICO_MINOR 9
#define ZENOH_PICO_PATCH 0
#define ZENOH_PICO_TWEAK 0

#include "zenoh-pico/api/admin_space.h"
#include "zenoh-pico/api/advanced_publisher.h"
#include "zenoh-pico/api/advanced_subscriber.h"
#include "zenoh-pico/api/constants.h"
#include "zenoh-pico/api/encoding.h"
#include "zenoh-pico/api/handlers.h"
#include "zenoh-pico/api/liveliness.h"
#include "zenoh-pico/api/macros.h"
#include "zenoh-pico/api/primitives.h"
#include "zenoh-pico/api/types.h"
#include "zenoh-pico/config.h"

#endif /* ZENOH_PICO_H */
