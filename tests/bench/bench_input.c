/* bench input: input-to-broadcast latency on the master.
 *
 * Per iteration: a DTrack datagram with a new wand pose leaves a UDP socket (t0); the
 * master side busy-polls input_poll() until the merged state shows the pose (t1), runs
 * interaction_update() in the lighting layout with C held so the flashlight follows (t2),
 * and sends the changed parameters over a real ZeroMQ PUB socket on TCP loopback to a SUB
 * socket that receives them (t3). The hop t2->t3 carries a fixed 64-byte record per
 * changed key (head, wand, light pose), the size the parameter wire format uses for mat4
 * values; the cluster master's own encoding and barrier are measured by bench cluster.
 * Also: DTrack parser throughput on a full 6-line datagram. Prints medians and p99 in us. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>
#include <zmq.h>

#include "bench.h"
#include "base/clock.h"
#include "input/input.h"
#include "input/input_dtrack.h"
#include "interaction.h"

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double pct(double *v, int n, double p)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    int i = (int)(p * (n - 1) + 0.5);
    return v[i];
}

int bench_input(int argc, char **argv)
{
    int iterations = 2000;
    const bench_option opts[] = {
        BENCH_INT("iterations", "N", "input polls measured", &iterations, 10, 100000000),
    };
    int pr = BENCH_PARSE("input", "input parsing and merging per master frame", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    char err[256];
    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_source *src = input_dtrack_open(&(input_dtrack_desc){.name = "bench"}, err, sizeof err);
    if (!in || !src || input_add_source(in, src, err, sizeof err)) {
        fprintf(stderr, "bench input: %s\n", err);
        return 1;
    }
    int port = input_dtrack_port(src);
    int tx = socket(AF_INET, SOCK_DGRAM, 0);
    struct sockaddr_in to = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port)};
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);

    void *zctx = zmq_ctx_new(), *pub = zmq_socket(zctx, ZMQ_PUB), *sub = zmq_socket(zctx, ZMQ_SUB);
    char ep[64];
    size_t eplen = sizeof ep;
    if (zmq_bind(pub, "tcp://127.0.0.1:*") || zmq_getsockopt(pub, ZMQ_LAST_ENDPOINT, ep, &eplen) ||
        zmq_setsockopt(sub, ZMQ_SUBSCRIBE, "", 0) || zmq_connect(sub, ep)) {
        fprintf(stderr, "bench input: ZeroMQ setup failed: %s\n", zmq_strerror(zmq_errno()));
        return 1;
    }
    /* PUB drops until the subscription has arrived: ping until one gets through. */
    for (int i = 0; i < 500; i++) {
        zmq_send(pub, "x", 1, 0);
        char b[4];
        if (zmq_recv(sub, b, sizeof b, ZMQ_DONTWAIT) >= 0)
            break;
        nanosleep(&(struct timespec){0, 2000000}, NULL);
    }

    interaction ia;
    interaction_init(&ia, &(interaction_desc){.first_layout = INTERACTION_LIGHTING});
    frame_params p;
    memset(&p, 0, sizeof p);
    for (int i = 0; i < 16; i += 5)
        p.head[i] = p.wand[i] = p.navigation[i] = 1.0f;
    p.light_count = 1;
    p.lights[0] = (frame_light){.enabled = 1, .color = {1, 1, 1}, .intensity = 10,
                                .outer_angle = 0.5f, .inner_angle = 0.4f};

    double *udp = malloc(sizeof(double) * (size_t)iterations * 4);
    double *ia_us = udp + iterations, *bc = ia_us + iterations, *total = bc + iterations;
    int timeouts = 0;
    uint8_t msg[4 * 66];
    for (int it = 0; it < iterations; it++) {
        char dg[512];
        float x = 100.0f + (float)it; /* millimetres: a new pose every iteration */
        int n = snprintf(dg, sizeof dg, "fr %d\n6d 1 [0 1.000][0 1700 0][1 0 0 0 1 0 0 0 1]\n"
                         "6df2 1 1 [0 1.000 4 2][%.1f 1200 -400][1 0 0 0 1 0 0 0 1][8 0 0]\n",
                         it, (double)x);
        input_state s;
        double t0 = clock_now_ms() * 1e3;
        sendto(tx, dg, (size_t)n, 0, (struct sockaddr *)&to, sizeof to);
        int seen = 0;
        for (double until = t0 + 1e6; !seen && clock_now_ms() * 1e3 < until;) {
            input_poll(in, &s, err, sizeof err);
            seen = s.wand.valid && s.wand.position[0] == (float)(x * 0.001); /* as the parser rounds */
        }
        if (!seen) {
            timeouts++;
            continue;
        }
        double t1 = clock_now_ms() * 1e3;
        uint32_t changed = interaction_update(&ia, &s, s.dt, &p);
        double t2 = clock_now_ms() * 1e3;
        size_t len = 0;
        if (changed & INTERACTION_CHANGED_WAND) {
            memcpy(msg + len, "\x01\x00", 2);
            memcpy(msg + len + 2, p.wand, 64);
            len += 66;
        }
        if (changed & INTERACTION_CHANGED_LIGHT) {
            memcpy(msg + len, "\x10\x00", 2);
            memcpy(msg + len + 2, &p.lights[0], sizeof p.lights[0]); /* 52 of 64 bytes */
            len += 66;
        }
        char rb[sizeof msg];
        zmq_send(pub, msg, len, 0);
        zmq_recv(sub, rb, sizeof rb, 0);
        double t3 = clock_now_ms() * 1e3;
        udp[it - timeouts] = t1 - t0;
        ia_us[it - timeouts] = t2 - t1;
        bc[it - timeouts] = t3 - t2;
        total[it - timeouts] = t3 - t0;
    }
    int ok = iterations - timeouts;

    /* Parser throughput on a full datagram. */
    const char full[] = "fr 21753\nts 39596.024831\n6dcal 2\n"
        "6d 2 [0 1.000][326.848 -187.216 1709.503][-0.940508 -0.339400 0.015209 0.328234 -0.919203 -0.217259 0.087754 -0.199394 0.976081] "
        "[1 1.000][-120.5 1100.25 -350.0][1 0 0 0 0 -1 0 1 0]\n"
        "6df2 1 1 [0 1.000 6 2][250.000 1200.500 -400.000][0 0 -1 0 1 0 1 0 0][5 -0.500000 0.750000]\n"
        "3d 2 [24 1.000][-42.400 1600.000 230.900] [25 1.000][10.0 20.0 30.0]\n";
    static input_dtrack_frame f;
    const int reps = 100000;
    double t0 = clock_now_ms() * 1e3;
    int bad = 0;
    for (int i = 0; i < reps; i++)
        bad += input_dtrack_parse(full, sizeof full - 1, &f);
    double parse_ns = (clock_now_ms() * 1e3 - t0) * 1000.0 / reps;

    if (ok < 10) {
        fprintf(stderr, "bench input: only %d of %d datagrams arrived\n", ok, iterations);
        return 1;
    }
    printf("{\"bench\":\"input\",\"source\":\"dtrack-udp-loopback\",\"iterations\":%d,\"lost\":%d,"
           "\"udp_to_state_us\":{\"median\":%.2f,\"p99\":%.2f},"
           "\"interaction_us\":{\"median\":%.3f,\"p99\":%.3f},"
           "\"zmq_broadcast_us\":{\"median\":%.2f,\"p99\":%.2f},"
           "\"input_to_broadcast_us\":{\"median\":%.2f,\"p99\":%.2f},"
           "\"dtrack_parse_ns_per_datagram\":%.0f,\"parse_errors\":%d}\n",
           iterations, timeouts, pct(udp, ok, 0.5), pct(udp, ok, 0.99), pct(ia_us, ok, 0.5),
           pct(ia_us, ok, 0.99), pct(bc, ok, 0.5), pct(bc, ok, 0.99), pct(total, ok, 0.5),
           pct(total, ok, 0.99), parse_ns, bad);
    free(udp);
    zmq_close(sub);
    zmq_close(pub);
    zmq_ctx_term(zctx);
    close(tx);
    input_close(in);
    return 0;
}
