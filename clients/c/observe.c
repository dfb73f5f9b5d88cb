/* telerobot-observe: a station's observation from C, through a Zenoh router.
 *
 * Zenoh's own C client (zenoh-pico, vendored in third_party/) subscribes to
 * telerobot/<station>/<topic>; each payload is parsed with the code protoc-c generates from
 * protos/, the schema every other client uses. One JSON line per message goes to stdout, and a
 * summary per topic at the end:
 *
 *   {"topic":"wrench","samples":10,"first":1201,"last":1210,"force_n":[0,0,-1.5],"lag_ms":2.1}
 *   {"topic":"state","sequence":88,"status":"ROBOT_STATUS_READY","joints_rad":[...],"tool_m":[...]}
 *   {"topic":"events","sequence":12,"event":"control_changed"}
 *   {"topic":"status","holders":["ann"],"waiters":[],"dependencies":{"proxy_robot":"DEPENDENCY_STATE_SERVING"}}
 *   {"topic":"video","content":"pair","sequence":40,"keyframe":true,"bytes":5321}
 *   {"summary":{"wrench":{"messages":100,"undecodable":0}, ...}}
 *
 * Endpoints follow the station's rule: tcp/HOST:PORT on loopback only, tls/HOST:PORT anywhere
 * with the station's PKI (--tls-dir, or TELEROBOT_TLS_DIR): mutual TLS, presenting
 * <identity>.pem (--identity, or TELEROBOT_IDENTITY; default observer) and checking the
 * router's certificate against ca.pem and the name in the endpoint. zenoh-pico's TLS comes from
 * Mbed TLS 3.6 (third_party/mbedtls): the routers speak TLS 1.3 only.
 *
 * Exit status: 0 when something arrived, 1 when nothing did (or the router did not answer),
 * 2 for bad arguments.
 */

#include <getopt.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <zenoh-pico.h>

#include "telerobot/v1/decision_server.pb-c.h"
#include "telerobot/v1/force_sensor.pb-c.h"
#include "telerobot/v1/proxy_robot.pb-c.h"
#include "telerobot/v1/stereo_camera.pb-c.h"

enum { WRENCH, STATE, EVENTS, STATUS, VIDEO, TOPIC_COUNT };
static const char *const TOPIC_NAMES[TOPIC_COUNT] = {"wrench", "state", "events", "status",
                                                      "video"};
/* What is followed unless --topics says otherwise: the video makes the station's cameras
 * render, so it is only for those who ask (wire/observation.py's DEFAULT_TOPICS). */
static const char *const DEFAULT_TOPICS = "wrench,state,events,status";

struct counts {
    long messages;
    long undecodable;
};

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static struct counts counts[TOPIC_COUNT];
static long total;
static volatile sig_atomic_t stopping;

static void on_signal(int sig) {
    (void)sig;
    stopping = 1;
}

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_REALTIME, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static double stamp_ms(const Google__Protobuf__Timestamp *stamp) {
    return stamp ? stamp->seconds * 1e3 + stamp->nanos / 1e6 : NAN;
}

/* A JSON string: operator ids and reasons are anyone's text. */
static void put_string(const char *text) {
    putchar('"');
    for (const unsigned char *c = (const unsigned char *)(text ? text : ""); *c; c++) {
        if (*c == '"' || *c == '\\') {
            printf("\\%c", *c);
        } else if (*c < 0x20) {
            printf("\\u%04x", *c);
        } else {
            putchar(*c);
        }
    }
    putchar('"');
}

static void put_number(double value) {
    if (isfinite(value)) {
        printf("%.6g", value);
    } else {
        printf("null");
    }
}

static void put_numbers(const double *values, size_t count) {
    putchar('[');
    for (size_t i = 0; i < count; i++) {
        if (i) putchar(',');
        put_number(values[i]);
    }
    putchar(']');
}

static void put_vector(const Telerobot__V1__Vector3 *v) {
    double values[3] = {NAN, NAN, NAN};
    if (v) {
        values[0] = v->x;
        values[1] = v->y;
        values[2] = v->z;
    }
    put_numbers(values, 3);
}

static const char *enum_name(const ProtobufCEnumDescriptor *descriptor, int value) {
    const ProtobufCEnumValue *found = protobuf_c_enum_descriptor_get_value(descriptor, value);
    return found ? found->name : "UNKNOWN";
}

/* The name of a oneof's field set, from its case (the field's number). */
static const char *case_name(const ProtobufCMessageDescriptor *descriptor, unsigned number) {
    const ProtobufCFieldDescriptor *field =
        protobuf_c_message_descriptor_get_field(descriptor, number);
    return field ? field->name : "none";
}

static int show_wrench(const uint8_t *data, size_t size) {
    Telerobot__V1__StreamWrenchResponse *m =
        telerobot__v1__stream_wrench_response__unpack(NULL, size, data);
    if (!m) return -1;
    printf("{\"topic\":\"wrench\",\"samples\":%zu", m->n_samples);
    if (m->n_samples) {
        const Telerobot__V1__WrenchSample *first = m->samples[0];
        const Telerobot__V1__WrenchSample *last = m->samples[m->n_samples - 1];
        printf(",\"first\":%lld,\"last\":%lld,\"force_n\":", (long long)first->sequence,
               (long long)last->sequence);
        put_vector(last->wrench ? last->wrench->force_n : NULL);
        printf(",\"torque_nm\":");
        put_vector(last->wrench ? last->wrench->torque_nm : NULL);
        printf(",\"lag_ms\":");
        put_number(now_ms() - stamp_ms(last->sample_time));
    }
    printf("}\n");
    telerobot__v1__stream_wrench_response__free_unpacked(m, NULL);
    return 0;
}

static int show_state(const uint8_t *data, size_t size) {
    Telerobot__V1__StreamStateResponse *m =
        telerobot__v1__stream_state_response__unpack(NULL, size, data);
    if (!m) return -1;
    const Telerobot__V1__RobotState *state = m->state;
    if (state) {
        printf("{\"topic\":\"state\",\"sequence\":%lld,\"status\":", (long long)state->sequence);
        put_string(enum_name(&telerobot__v1__robot_status__descriptor, state->status));
        printf(",\"joints_rad\":");
        put_numbers(state->joint_positions_rad, state->n_joint_positions_rad);
        printf(",\"tool_m\":");
        put_vector(state->tool_pose ? state->tool_pose->position_m : NULL);
        printf(",\"lag_ms\":");
        put_number(now_ms() - stamp_ms(state->sample_time));
        printf("}\n");
    } else {
        printf("{\"topic\":\"state\"}\n");
    }
    telerobot__v1__stream_state_response__free_unpacked(m, NULL);
    return 0;
}

static int show_event(const uint8_t *data, size_t size) {
    Telerobot__V1__StreamEventsResponse *m =
        telerobot__v1__stream_events_response__unpack(NULL, size, data);
    if (!m) return -1;
    printf("{\"topic\":\"events\",\"sequence\":%lld,\"event\":", (long long)m->sequence);
    put_string(case_name(&telerobot__v1__stream_events_response__descriptor, m->event_case));
    printf("}\n");
    telerobot__v1__stream_events_response__free_unpacked(m, NULL);
    return 0;
}

static void put_operators(Telerobot__V1__ControlHolder *const *holders, size_t count) {
    putchar('[');
    for (size_t i = 0; i < count; i++) {
        if (i) putchar(',');
        put_string(holders[i]->operator_id);
    }
    putchar(']');
}

static int show_status(const uint8_t *data, size_t size) {
    Telerobot__V1__SessionStatus *m = telerobot__v1__session_status__unpack(NULL, size, data);
    if (!m) return -1;
    printf("{\"topic\":\"status\",\"holders\":");
    put_operators(m->control ? m->control->holders : NULL, m->control ? m->control->n_holders : 0);
    printf(",\"waiters\":");
    put_operators(m->control ? m->control->waiters : NULL, m->control ? m->control->n_waiters : 0);
    printf(",\"dependencies\":{");
    for (size_t i = 0; i < m->n_dependencies; i++) {
        if (i) putchar(',');
        put_string(m->dependencies[i]->name);
        putchar(':');
        put_string(enum_name(&telerobot__v1__dependency_state__descriptor,
                             m->dependencies[i]->state));
    }
    printf("}}\n");
    telerobot__v1__session_status__free_unpacked(m, NULL);
    return 0;
}

static int show_video(const uint8_t *data, size_t size) {
    Telerobot__V1__StreamPairsResponse *m =
        telerobot__v1__stream_pairs_response__unpack(NULL, size, data);
    if (!m) return -1;
    printf("{\"topic\":\"video\",\"content\":");
    put_string(case_name(&telerobot__v1__stream_pairs_response__descriptor, m->content_case));
    if (m->content_case == TELEROBOT__V1__STREAM_PAIRS_RESPONSE__CONTENT_PAIR) {
        printf(",\"sequence\":%lld,\"keyframe\":%s,\"bytes\":%zu", (long long)m->pair->sequence,
               m->pair->keyframe ? "true" : "false", m->pair->video_frame.len);
    } else if (m->content_case == TELEROBOT__V1__STREAM_PAIRS_RESPONSE__CONTENT_HEADER) {
        printf(",\"width_px\":%d,\"height_px\":%d", m->header->width_px, m->header->height_px);
    }
    printf("}\n");
    telerobot__v1__stream_pairs_response__free_unpacked(m, NULL);
    return 0;
}

static int (*const SHOW[TOPIC_COUNT])(const uint8_t *, size_t) = {
    show_wrench, show_state, show_event, show_status, show_video};

/* Each subscriber's context is its topic's index in TOPIC_NAMES. */
static void on_sample(z_loaned_sample_t *sample, void *context) {
    int topic = (int)(intptr_t)context;
    z_owned_slice_t payload;
    if (z_bytes_to_slice(z_sample_payload(sample), &payload) != Z_OK) return;
    pthread_mutex_lock(&lock);
    if (SHOW[topic](z_slice_data(z_loan(payload)), z_slice_len(z_loan(payload))) == 0) {
        counts[topic].messages++;
        total++;
    } else {
        counts[topic].undecodable++;
        fprintf(stderr, "telerobot-observe: a %s payload of %zu bytes is no message of its "
                "topic's type: left out\n", TOPIC_NAMES[topic], z_slice_len(z_loan(payload)));
    }
    fflush(stdout);
    pthread_mutex_unlock(&lock);
    z_drop(z_move(payload));
}

/* tcp/ADDRESS:PORT with a loopback address: the only plaintext endpoint this client may use. */
static int loopback_endpoint(const char *endpoint) {
    static const char *const ALLOWED[] = {"tcp/127.", "tcp/localhost:", "tcp/[::1]:"};
    for (size_t i = 0; i < sizeof ALLOWED / sizeof *ALLOWED; i++) {
        if (strncmp(endpoint, ALLOWED[i], strlen(ALLOWED[i])) == 0) {
            return strrchr(endpoint, ':') != NULL;
        }
    }
    return 0;
}

/* <tls_dir>/<name><suffix>, if it is there; else says which file is missing. */
static int tls_file(char *path, size_t size, const char *tls_dir, const char *name,
                    const char *suffix) {
    snprintf(path, size, "%s/%s%s", tls_dir, name, suffix);
    if (access(path, R_OK) == 0) return 1;
    fprintf(stderr, "telerobot-observe: TLS needs %s: `make certs` issues it\n", path);
    return 0;
}

/* Mutual TLS with the station's PKI: ca.pem checks the router, <identity>.pem speaks for us. */
static int insert_tls(z_owned_config_t *config, const char *tls_dir, const char *identity) {
    char ca[4096], cert[4096], key[4096];
    if (!tls_file(ca, sizeof ca, tls_dir, "ca", ".pem") ||
        !tls_file(cert, sizeof cert, tls_dir, identity, ".pem") ||
        !tls_file(key, sizeof key, tls_dir, identity, ".key")) {
        return 0;
    }
    zp_config_insert(z_loan_mut(*config), Z_CONFIG_TLS_ROOT_CA_CERTIFICATE_KEY, ca);
    zp_config_insert(z_loan_mut(*config), Z_CONFIG_TLS_ENABLE_MTLS_KEY, "true");
    zp_config_insert(z_loan_mut(*config), Z_CONFIG_TLS_CONNECT_CERTIFICATE_KEY, cert);
    zp_config_insert(z_loan_mut(*config), Z_CONFIG_TLS_CONNECT_PRIVATE_KEY_KEY, key);
    return 1;
}

static int station_name_ok(const char *name) {
    size_t length = strlen(name);
    if (length < 1 || length > 64) return 0;
    return strspn(name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-") ==
           length;
}

static int usage(const char *why) {
    fprintf(stderr,
            "telerobot-observe: %s\n"
            "usage: telerobot-observe --router tcp/127.0.0.1:PORT | tls/HOST:PORT\n"
            "       [--tls-dir DIR] [--identity NAME] [--station NAME]\n"
            "       [--topics wrench,state,events,status,video] [--count N] [--seconds S]\n",
            why);
    return 2;
}

int main(int argc, char **argv) {
    const char *router = NULL, *station = getenv("TELEROBOT_STATION");
    const char *tls_dir = getenv("TELEROBOT_TLS_DIR"), *identity = getenv("TELEROBOT_IDENTITY");
    char topics_arg[128];
    snprintf(topics_arg, sizeof topics_arg, "%s", DEFAULT_TOPICS);
    long count = 0;
    double seconds = 0;
    static const struct option OPTIONS[] = {
        {"router", required_argument, NULL, 'r'}, {"station", required_argument, NULL, 's'},
        {"topics", required_argument, NULL, 't'}, {"count", required_argument, NULL, 'n'},
        {"seconds", required_argument, NULL, 'S'}, {"tls-dir", required_argument, NULL, 'd'},
        {"identity", required_argument, NULL, 'i'}, {NULL, 0, NULL, 0}};
    for (int opt; (opt = getopt_long(argc, argv, "", OPTIONS, NULL)) != -1;) {
        switch (opt) {
            case 'r': router = optarg; break;
            case 's': station = optarg; break;
            case 't': snprintf(topics_arg, sizeof topics_arg, "%s", optarg); break;
            case 'n': count = atol(optarg); break;
            case 'S': seconds = atof(optarg); break;
            case 'd': tls_dir = optarg; break;
            case 'i': identity = optarg; break;
            default: return usage("unknown option");
        }
    }
    if (!station || !*station) station = "station";
    if (!identity || !*identity) identity = "observer";
    if (!router) return usage("--router is required");
    int tls = strncmp(router, "tls/", 4) == 0 && strrchr(router, ':') != NULL;
    if (tls && (!tls_dir || !*tls_dir)) {
        return usage("the router's endpoint is TLS: give the station's TLS directory (--tls-dir, "
                     "or TELEROBOT_TLS_DIR)");
    }
    if (!tls && !loopback_endpoint(router)) {
        return usage("the router must be tcp/ on loopback (plaintext goes no further) or tls/");
    }
    if (!station_name_ok(station)) return usage("station name: use 1-64 of A-Z a-z 0-9 _ -");
    int wanted[TOPIC_COUNT] = {0};
    for (char *save, *name = strtok_r(topics_arg, ",", &save); name;
         name = strtok_r(NULL, ",", &save)) {
        int found = -1;
        for (int t = 0; t < TOPIC_COUNT; t++) {
            if (strcmp(name, TOPIC_NAMES[t]) == 0) found = t;
        }
        if (found < 0) return usage("unknown topic; known: wrench, state, events, status, video");
        wanted[found] = 1;
    }

    z_owned_config_t config;
    z_config_default(&config);
    zp_config_insert(z_loan_mut(config), Z_CONFIG_MODE_KEY, "client");
    zp_config_insert(z_loan_mut(config), Z_CONFIG_CONNECT_KEY, router);
    if (tls && !insert_tls(&config, tls_dir, identity)) {
        z_drop(z_move(config));
        return 2;
    }
    z_owned_session_t session;
    if (z_open(&session, z_move(config), NULL) < 0) {
        fprintf(stderr, "telerobot-observe: the router %s does not answer\n", router);
        return 1;
    }
    z_owned_subscriber_t subscribers[TOPIC_COUNT];
    int declared[TOPIC_COUNT] = {0};
    for (int t = 0; t < TOPIC_COUNT; t++) {
        if (!wanted[t]) continue;
        char key[128];
        snprintf(key, sizeof key, "telerobot/%s/%s", station, TOPIC_NAMES[t]);
        z_view_keyexpr_t key_expr;
        z_owned_closure_sample_t callback;
        z_view_keyexpr_from_str(&key_expr, key);
        z_closure(&callback, on_sample, NULL, (void *)(intptr_t)t);
        if (z_declare_subscriber(z_loan(session), &subscribers[t], z_loan(key_expr),
                                 z_move(callback), NULL) < 0) {
            fprintf(stderr, "telerobot-observe: cannot subscribe to %s\n", key);
            continue;
        }
        declared[t] = 1;
    }
    fprintf(stderr, "telerobot-observe: following station %s through %s\n", station, router);

    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    double deadline = seconds > 0 ? now_ms() + seconds * 1e3 : INFINITY;
    for (;;) {
        pthread_mutex_lock(&lock);
        long seen = total;
        pthread_mutex_unlock(&lock);
        if (stopping || (count > 0 && seen >= count) || now_ms() >= deadline) break;
        usleep(10000);
    }
    for (int t = 0; t < TOPIC_COUNT; t++) {
        if (declared[t]) z_drop(z_move(subscribers[t]));
    }
    z_drop(z_move(session));

    pthread_mutex_lock(&lock);
    printf("{\"summary\":{");
    int first = 1;
    for (int t = 0; t < TOPIC_COUNT; t++) {
        if (!wanted[t]) continue;
        printf("%s\"%s\":{\"messages\":%ld,\"undecodable\":%ld}", first ? "" : ",", TOPIC_NAMES[t],
               counts[t].messages, counts[t].undecodable);
        first = 0;
    }
    printf("}}\n");
    long received = total;
    pthread_mutex_unlock(&lock);
    return received > 0 ? 0 : 1;
}
