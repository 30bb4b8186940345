// Thread-safety stress test of the bezjoin C ABI (issue 10).
//
//   stress [iterations_per_thread=100000] [threads=8]
//
// 1. Shared read-only handles (curves of degree 0..12 in dimension 1..4) are
//    created once. Each worker w runs a deterministic pseudo-random sequence
//    of `iterations` mixed calls on them (eval with derivatives, segment with
//    extrapolation, split, arc length, degree elevation, reverse, points,
//    merge, connect and intersection of two shared curves, including calls
//    that fail on purpose),
//    frees every handle it gets, and folds every status and every output
//    double's bit pattern into an FNV-1a checksum.
// 2. Reference: all workers run one after another on the main thread.
//    Concurrent: all workers run at once, one thread each. Every worker's
//    checksum must be bit-for-bit the reference one.
// 3. Per-thread last error: in rounds, every thread provokes its own error
//    (split at t = 10.25 + thread), waits at a barrier until all threads
//    have provoked theirs, then reads bzj_last_error() back and requires its
//    own value, none of the others'; then a successful call must leave its
//    message empty while the others still hold theirs.
// Exit status 0 only if everything matched. Build and run: scripts/ci-embedding.sh
// (also under valgrind --tool=helgrind with fewer iterations, and with
// -fsanitize=thread on the C++ side).
#include <bezjoin.h>

#include <pthread.h>

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

struct Checksum {
    uint64_t h = 1469598103934665603ull;
    void add_u64(uint64_t v) {
        for (int i = 0; i < 8; ++i) {
            h ^= (v >> (8 * i)) & 0xff;
            h *= 1099511628211ull;
        }
    }
    void add(double x) {
        uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        add_u64(bits);
    }
};

struct Rng {  // xorshift64*: the same sequence on every run and thread
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
    uint64_t next() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return s * 2685821657736338717ull;
    }
    double uniform(double lo, double hi) { return lo + (hi - lo) * ((next() >> 11) * 0x1.0p-53); }
    size_t below(size_t n) { return static_cast<size_t>(next() % n); }
};

std::vector<BzjCurve*> g_curves;
int g_failures = 0;  // written only by the main thread

void fold_curve(Checksum& sum, const BzjCurve* c) {
    size_t degree = 0, dim = 0;
    sum.add_u64(static_cast<uint64_t>(bzj_curve_degree(c, &degree)));
    sum.add_u64(static_cast<uint64_t>(bzj_curve_dim(c, &dim)));
    sum.add_u64(degree);
    sum.add_u64(dim);
    double buf[64 * 4];
    const size_t n = (degree + 1) * dim;
    if (n <= sizeof buf / sizeof buf[0]) {
        sum.add_u64(static_cast<uint64_t>(bzj_curve_points(c, buf, n)));
        for (size_t i = 0; i < n; ++i) sum.add(buf[i]);
    }
}

struct WorkerResult {
    uint64_t checksum = 0;
    long internal_errors = 0;  // BZJ_ERR_INTERNAL: a caught panic, always a bug
};

WorkerResult worker(unsigned id, long iterations) {
    Rng rng(id + 1);
    Checksum sum;
    long internal_errors = 0;
    double buf[16 * 4];
    for (long i = 0; i < iterations; ++i) {
        const BzjCurve* c = g_curves[rng.below(g_curves.size())];
        BzjStatus st;
        // Merge, connect and intersect (the slow ones) in 1 of 64 calls each,
        // the others about 1 in 8.
        const size_t r = rng.below(64);
        switch (r == 0 ? 7 : r == 1 ? 9 : r == 2 ? 10 : (r % 8 == 7 ? 8 : r % 8)) {
            case 0:
            case 1: {  // eval, value and derivatives, inside and outside [0, 1]
                const size_t order = rng.below(5);
                st = bzj_curve_eval(c, rng.uniform(-0.5, 1.5), order, buf, sizeof buf / sizeof buf[0]);
                sum.add_u64(static_cast<uint64_t>(st));
                size_t dim = 0;
                bzj_curve_dim(c, &dim);
                if (st == BZJ_OK)
                    for (size_t k = 0; k < (order + 1) * dim; ++k) sum.add(buf[k]);
                break;
            }
            case 2: {  // segment with extrapolation and reversed ranges
                BzjCurve* out = nullptr;
                st = bzj_curve_segment(c, rng.uniform(-1, 2), rng.uniform(-1, 2), &out);
                sum.add_u64(static_cast<uint64_t>(st));
                if (out) fold_curve(sum, out);
                bzj_curve_free(out);
                break;
            }
            case 3: {  // split, sometimes outside [0, 1] (an error on purpose)
                BzjCurve *left = nullptr, *right = nullptr;
                st = bzj_curve_split(c, rng.uniform(-0.1, 1.1), &left, &right);
                sum.add_u64(static_cast<uint64_t>(st));
                if (left) fold_curve(sum, left);
                if (right) fold_curve(sum, right);
                bzj_curve_free(left);
                bzj_curve_free(right);
                break;
            }
            case 4: {  // arc length
                double len = 0;
                st = bzj_curve_length(c, rng.uniform(-0.2, 1.2), rng.uniform(-0.2, 1.2), &len);
                sum.add_u64(static_cast<uint64_t>(st));
                sum.add(len);
                break;
            }
            case 5: {  // elevation by 0..3 (and a refused reduction)
                size_t degree = 0;
                bzj_curve_degree(c, &degree);
                size_t target = degree + rng.below(4);
                if (degree > 0 && rng.below(8) == 0) target = degree - 1;
                BzjCurve* out = nullptr;
                st = bzj_curve_elevate(c, target, &out);
                sum.add_u64(static_cast<uint64_t>(st));
                if (out) fold_curve(sum, out);
                bzj_curve_free(out);
                break;
            }
            case 6: {  // reverse
                BzjCurve* out = nullptr;
                st = bzj_curve_reverse(c, &out);
                sum.add_u64(static_cast<uint64_t>(st));
                if (out) fold_curve(sum, out);
                bzj_curve_free(out);
                break;
            }
            case 7: {  // merge two shared curves of the same dimension
                static const size_t pairs[][2] = {{1, 2}, {2, 7}, {3, 5}, {7, 1}, {0, 6}};
                const size_t* pair = pairs[rng.below(5)];
                BzjMergeOptions options;
                std::memset(&options, 0, sizeof options);
                options.metric = rng.below(2) ? BZJ_METRIC_L2 : BZJ_METRIC_DISCRETE;
                const size_t split = rng.below(3);
                options.split = split == 0 ? BZJ_SPLIT_GIVEN : split == 1 ? BZJ_SPLIT_HALF : BZJ_SPLIT_POLYGON;
                options.mu = rng.uniform(0.2, 0.8);
                options.fix_ends = rng.below(2) == 0;
                BzjCurve *merged = nullptr, *p_hat = nullptr, *q_hat = nullptr;
                BzjMergeReport report;
                std::memset(&report, 0, sizeof report);
                st = bzj_merge(g_curves[pair[0]], g_curves[pair[1]], &options, &merged, &p_hat, &q_hat, &report);
                sum.add_u64(static_cast<uint64_t>(st));
                if (st == BZJ_OK) {
                    sum.add(report.mu);
                    sum.add(report.metric_value);
                    sum.add(report.max_deviation);
                }
                for (BzjCurve* h : {merged, p_hat, q_hat}) {
                    if (h) fold_curve(sum, h);
                    bzj_curve_free(h);
                }
                break;
            }
            case 9: {  // connect two shared curves of the same dimension, C^1 at both ends
                static const size_t pairs[][2] = {{1, 2}, {2, 7}, {3, 5}, {7, 1}};
                const size_t* pair = pairs[rng.below(4)];
                BzjConnectOptions options;
                std::memset(&options, 0, sizeof options);
                options.p_order = 1;
                options.q_order = rng.below(2);
                options.p_scale = 1.0;
                options.q_scale = 1.0;
                BzjCurve* out = nullptr;
                st = bzj_connect(g_curves[pair[0]], rng.uniform(0.3, 0.9), g_curves[pair[1]], rng.uniform(0.1, 0.7),
                                 &options, &out);
                sum.add_u64(static_cast<uint64_t>(st));
                if (out) fold_curve(sum, out);
                bzj_curve_free(out);
                break;
            }
            case 10: {  // crossings of two shared planar curves
                static const size_t pairs[][2] = {{1, 2}, {2, 7}, {7, 1}};
                const size_t* pair = pairs[rng.below(3)];
                double crossings[2 * 8];
                size_t count = 0;
                st = bzj_intersect(g_curves[pair[0]], g_curves[pair[1]], crossings, 8, &count);
                sum.add_u64(static_cast<uint64_t>(st));
                sum.add_u64(count);
                if (st == BZJ_OK)
                    for (size_t k = 0; k < 2 * (count < 8 ? count : 8); ++k) sum.add(crossings[k]);
                break;
            }
            default: {  // a non-finite parameter: an error on purpose
                st = bzj_curve_eval(c, rng.below(2) ? std::nan("") : HUGE_VAL, 0, buf, 4);
                sum.add_u64(static_cast<uint64_t>(st));
                break;
            }
        }
        if (st == BZJ_ERR_INTERNAL && internal_errors++ == 0)
            std::fprintf(stderr, "worker %u call %ld: BZJ_ERR_INTERNAL: %s\n", id, i, bzj_last_error());
    }
    return WorkerResult{sum.h, internal_errors};
}

struct ErrorRounds {
    pthread_barrier_t barrier;
    unsigned threads;
    int rounds;
    std::vector<int> failures;  // one slot per thread
};

std::string expected_value(unsigned id) {
    char text[32];
    std::snprintf(text, sizeof text, "t = %g ", 10.25 + id);
    return text;
}

void error_worker(ErrorRounds* r, unsigned id) {
    const BzjCurve* c = g_curves[id % g_curves.size()];
    const std::string mine = expected_value(id);
    for (int round = 0; round < r->rounds; ++round) {
        BzjCurve *left = nullptr, *right = nullptr;
        if (bzj_curve_split(c, 10.25 + id, &left, &right) != BZJ_ERR_INVALID_ARGUMENT) ++r->failures[id];
        pthread_barrier_wait(&r->barrier);  // every thread now holds its own error
        const std::string got = bzj_last_error();
        if (got.find(mine) == std::string::npos) ++r->failures[id];
        for (unsigned other = 0; other < r->threads; ++other)
            if (other != id && got.find(expected_value(other)) != std::string::npos) ++r->failures[id];
        pthread_barrier_wait(&r->barrier);
        // Even threads succeed now; odd threads' messages must survive that.
        if (id % 2 == 0) {
            size_t degree = 0;
            if (bzj_curve_degree(c, &degree) != BZJ_OK) ++r->failures[id];
        }
        pthread_barrier_wait(&r->barrier);
        const std::string after = bzj_last_error();
        if (id % 2 == 0 ? !after.empty() : after.find(mine) == std::string::npos) ++r->failures[id];
        pthread_barrier_wait(&r->barrier);
    }
}

BzjCurve* make_curve(size_t dim, size_t degree, uint64_t seed) {
    Rng rng(seed);
    std::vector<double> pts((degree + 1) * dim);
    for (double& p : pts) p = rng.uniform(-10, 10);
    BzjCurve* c = nullptr;
    if (bzj_curve_new(dim, degree, pts.data(), pts.size(), &c) != BZJ_OK) {
        std::fprintf(stderr, "curve_new failed: %s\n", bzj_last_error());
        std::exit(2);
    }
    return c;
}

}  // namespace

int main(int argc, char** argv) {
    const long iterations = argc > 1 ? std::atol(argv[1]) : 100000;
    const unsigned threads = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 8;
    if (iterations <= 0 || threads == 0) {
        std::fprintf(stderr, "usage: %s [iterations>0] [threads>0]\n", argv[0]);
        return 2;
    }
    const size_t shapes[][2] = {{1, 0}, {2, 1}, {2, 3}, {3, 5}, {4, 7}, {3, 12}, {1, 9}, {2, 2}};
    uint64_t seed = 100;
    for (const auto& s : shapes) g_curves.push_back(make_curve(s[0], s[1], seed++));

    std::vector<WorkerResult> reference(threads), concurrent(threads);
    for (unsigned w = 0; w < threads; ++w) reference[w] = worker(w, iterations);

    std::vector<std::thread> pool;
    for (unsigned w = 0; w < threads; ++w)
        pool.emplace_back([&concurrent, w, iterations] { concurrent[w] = worker(w, iterations); });
    for (auto& t : pool) t.join();
    pool.clear();
    for (unsigned w = 0; w < threads; ++w) {
        if (reference[w].checksum != concurrent[w].checksum) {
            std::fprintf(stderr, "FAIL worker %u: checksum %016" PRIx64 " concurrent, %016" PRIx64 " alone\n", w,
                         concurrent[w].checksum, reference[w].checksum);
            ++g_failures;
        }
        if (reference[w].internal_errors + concurrent[w].internal_errors != 0) {
            std::fprintf(stderr, "FAIL worker %u: %ld calls returned BZJ_ERR_INTERNAL\n", w,
                         reference[w].internal_errors + concurrent[w].internal_errors);
            ++g_failures;
        }
    }

    ErrorRounds rounds;
    rounds.threads = threads;
    rounds.rounds = static_cast<int>(iterations / 1000 > 0 ? (iterations / 1000 < 100 ? iterations / 1000 : 100) : 1);
    rounds.failures.assign(threads, 0);
    pthread_barrier_init(&rounds.barrier, nullptr, threads);
    for (unsigned w = 0; w < threads; ++w) pool.emplace_back(error_worker, &rounds, w);
    for (auto& t : pool) t.join();
    pthread_barrier_destroy(&rounds.barrier);
    for (unsigned w = 0; w < threads; ++w) {
        if (rounds.failures[w] != 0) {
            std::fprintf(stderr, "FAIL thread %u: %d per-thread error message check(s) failed\n", w, rounds.failures[w]);
            ++g_failures;
        }
    }

    for (BzjCurve* c : g_curves) bzj_curve_free(c);
    if (g_failures != 0) return 1;
    std::printf("stress: %u threads x %ld calls: checksums identical to the single-threaded run; "
                "%d rounds of per-thread last-error checks passed\n",
                threads, iterations, rounds.rounds);
    return 0;
}
