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

#ifndef INCLUDE_ZENOH_PICO_SESSION_SUBSCRIPTION_H
#define INCLUDE_ZENOH_PICO_SESSION_SUBSCRIPTION_H

#include "zenoh-pico/net/encoding.h"
#include "zenoh-pico/protocol/core.h"
#include "zenoh-pico/session/resource.h"
#include "zenoh-pico/session/session.h"

#ifdef __cplusplus
extern "C" {
#endif

// Forward declaration to avoid cyclical include
typedef struct _z_session_t _z_session_t;

_Z_SVEC_DEFINE(_z_subscription_rc, _z_subscription_rc_t)

/*------------------ Subscription ------------------*/
z_result_t _z_trigger_liveliness_subscriptions_declare(_z_session_t *zn, const _z_keyexpr_t *keyexpr,
                                                       const _z_timestamp_t *timestamp,
                                                       _z_transport_peer_common_t *peer);

z_result_t _z_trigger_liveliness_subscriptions_undeclare(_z_session_t *zn, const _z_keyexpr_t *keyexpr,
                                                         const _z_timestamp_t *timestamp);

#if Z_FEATURE_SUBSCRIPTION == 1

_z_subscription_rc_t _z_get_subscription_by_id(_z_session_t *zn, _z_subscriber_kind_t kind, const _z_zint_t id);
_z_subscription_rc_t _z_register_subscription(_z_session_t *zn, _z_subscriber_kind_t kind, _z_subscription_t *sub);
z_result_t _z_trigger_subscriptions_impl(_z_session_t *zn, _z_subscriber_kind_t sub_kind, const _z_keyexpr_t *keyexpr,
                                         const _z_bytes_t *opt_payload, const _z_encoding_t *opt_encoding,
                                         const _z_zint_t sample_kind, const _z_timestamp_t *opt_timestamp,
                                         _z_n_qos_t qos, const _z_bytes_t *opt_attachment, z_reliability_t reliability,
                                         const _z_source_info_t *opt_source_info, _z_transport_peer_common_t *peer);
void _z_unregister_subscription(_z_session_t *zn, _z_subscriber_kind_t kind, _z_subscription_rc_t *sub);
void _z_flush_subscriptions(_z_session_t *zn);

static inline z_result_t _z_trigger_subscriptions_put(_z_session_t *zn, const _z_wireexpr_t *wireexpr,
                                                      const _z_bytes_t *payload, const _z_encoding_t *encoding,
                                                      const _z_timestamp_t *timestamp, _z_n_qos_t qos,
                                                      const _z_bytes_t *attachment, z_reliability_t reliability,
                                                      const _z_source_info_t *source_info,
                                                      _z_transport_peer_common_t *peer) {
    _z_keyexpr_view_t ke_view;
    char buf[Z_MAX_KEYEXPR_LENGTH];
    _Z_RETURN_IF_ERR(_z_get_keyexpr_view_from_wireexpr(zn, &ke_view, wireexpr, peer, buf, Z_MAX_KEYEXPR_LENGTH));
    return _z_trigger_subscriptions_impl(zn, _Z_SUBSCRIBER_KIND_SUBSCRIBER, _z_keyexpr_view_deref(&ke_view), payload,
                                         encoding, Z_SAMPLE_KIND_PUT, timestamp, qos, attachment, reliability,
                                         source_info, peer);
}
static inline z_result_t _z_trigger_subscriptions_del(_z_session_t *zn, const _z_wireexpr_t *wireexpr,
                                                      const _z_timestamp_t *timestamp, const _z_n_qos_t qos,
                                                      const _z_bytes_t *attachment, z_reliability_t reliability,
                                                      const _z_source_info_t *source_info,
                                                      _z_transport_peer_common_t *peer) {
    _z_keyexpr_view_t ke_view;
    char buf[Z_MAX_KEYEXPR_LENGTH];
    _Z_RETURN_IF_ERR(_z_get_keyexpr_view_from_wireexpr(zn, &ke_view, wireexpr, peer, buf, Z_MAX_KEYEXPR_LENGTH));
    return _z_trigger_subscriptions_impl(zn, _Z_SUBSCRIBER_KIND_SUBSCRIBER, _z_keyexpr_view_deref(&ke_view), NULL, NULL,
                                         Z_SAMPLE_KIND_DELETE, timestamp, qos, attachment, reliability, source_info,
                                         peer);
}
#else   // Z_FEATURE_SUBSCRIPTION == 0
static inline z_result_t _z_trigger_subscriptions_put(_z_session_t *zn, const _z_wireexpr_t *wireexpr,
                                                      const _z_bytes_t *payload, const _z_encoding_t *encoding,
                                                      const _z_timestamp_t *timestamp, _z_n_qos_t qos,
                                                      const _z_bytes_t *attachment, z_reliability_t reliability,
                                                      const _z_source_info_t *source_info,
                                                      _z_transport_peer_common_t *peer) {
    _ZP_UNUSED(zn);
    _ZP_UNUSED(wireexpr);
    _ZP_UNUSED(payload);
    _ZP_UNUSED(encoding);
    _ZP_UNUSED(qos);
    _ZP_UNUSED(timestamp);
    _ZP_UNUSED(attachment);
    _ZP_UNUSED(reliability);
    _ZP_UNUSED(source_info);
    _ZP_UNUSED(peer);
    return _Z_RES_OK;
}

static inline z_result_t _z_trigger_subscriptions_del(_z_session_t *zn, const _z_wireexpr_t *wireexpr,
                                                      const _z_timestamp_t *timestamp, const _z_n_qos_t qos,
                                                      const _z_bytes_t *attachment, z_reliability_t reliability,
                                                      const _z_source_info_t *source_info,
                                                      _z_transport_peer_common_t *peer) {
    _ZP_UNUSED(zn);
    _ZP_UNUSED(wireexpr);
    _ZP_UNUSED(qos);
    _ZP_UNUSED(timestamp);
    _ZP_UNUSED(attachment);
    _ZP_UNUSED(reliability);
    _ZP_UNUSED(source_info);
    _ZP_UNUSED(peer);
    return _Z_RES_OK;
}
#endif  // Z_FEATURE_SUBSCRIPTION == 1

#ifdef __cplusplus
}
#endif

#endif /* INCLUDE_ZENOH_PICO_SESSION_SUBSCRIPTION_H */
