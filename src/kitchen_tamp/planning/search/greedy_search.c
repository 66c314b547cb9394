/* The lazy alternating greedy search of alternating_greedy._lazy, in C.

   The same search as the Python one and as greedy_kernel.py (numba), step for
   step: h_add's exploration with its buckets first-in first-out (costs from
   bucket_levels on in a heap, the same order), the best supporters' relaxed
   plan and its applicable actions, the landmark count and its preferred
   operators, the queues (h_FF's all and preferred, the landmark count's all and
   preferred, the novel one), their turns and boosts, ties first-in first-out,
   and the successor order of Task.successor_indices. So it expands the states
   the Python search would, in the same order, and returns the same plan and
   counts.

   It exists so that handing a search over costs a process neither numpy nor
   numba: numba's kernel needs numpy's import (about 0.05 s of CPU) and numba's
   (most of a second), more than most searches take; this file builds into a
   shared library that ctypes loads in a few milliseconds (native_greedy.py
   builds and calls it). Plain C99, no Python API. The arrays an evaluation
   streams through (users, adds, precondition and unsettled counts) are 32-bit:
   half the memory traffic on large tasks.

   A state is a row of state_bytes bytes (bit i: atom i). Evaluated states are
   rows of one growing table found again through an open-addressing hash table;
   a queued entry is a (parent row, action) pair whose child is computed again
   when it is taken out, as Fast Downward's lazy search does.

   greedy_portfolio runs several such searches of one task, with other choices
   of heuristics and queues (partners.py), taking turns counted in evaluations;
   each keeps its state (struct Search) between turns. One search alone is the
   portfolio of one. */

#define _POSIX_C_SOURCE 199309L /* clock_gettime under -std=c99 */

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef int64_t i64;
typedef uint8_t u8;
typedef int32_t i32; /* the task's indices and counts: half the memory an evaluation streams through */

enum { SOLVED = 0, UNSOLVABLE = 1, OUT_OF_BUDGET = 2, OUT_OF_MEMORY = 3, RUNNING = 4 };

#define PORTFOLIO_MAX 8 /* searches taking turns at most */

#define ORDER_BITS 40     /* bits of a queue key below h: the push's number */
#define SEQUENCE_BITS 32  /* bits of an exploration heap key below the cost: the offer's number */
#define CLOCK_EVERY 64    /* the clock is read every this many expansions */
#define UNREACHED (((i64)1) << 62)

/* The task as flat arrays (CSR: xs_start[i]..xs_start[i + 1] index xs for row i). */
struct GreedyTask {
    i64 n_atoms, n_actions, state_bytes, bucket_levels;
    const u8 *root, *goal, *goal_neg;
    const i64 *unconditional; /* actions without positive preconditions */
    i64 n_unconditional;
    const i64 *key_start, *key_actions; /* per atom, the actions keyed on it */
    const i64 *pre_start, *pres, *neg_start, *negs;
    const i32 *add_start, *adds;
    const i64 *delete_start, *deletes;
    const i32 *users_start, *users;     /* per atom, the relevant actions it is a precondition of */
    const i32 *precondition_counts;     /* per action */
    const i64 *free_actions;            /* relevant actions without preconditions */
    i64 n_free_actions;
    const i64 *goal_ids;
    i64 n_goal_ids;
    i64 landmarks_used, landmark_preferred, n_landmarks;
    const i64 *landmark_atoms;
    const u8 *landmark_goal, *natural, *greedy_necessary; /* rows of state_bytes per landmark */
    const i64 *achievers_start, *achievers;
};

struct GreedySettings {
    i64 heuristics, boost, novelty, max_expansions; /* max_expansions < 0: none */
    double deadline;                                /* on CLOCK_MONOTONIC, seconds; < 0: none */
};

struct GreedyResult {
    i64 outcome, goal_row, expanded, generated, evaluated, n_rows;
    i64 *parents, *actions; /* per evaluated row; freed by greedy_result_free */
};

/* Work space of one evaluation. */
struct Evaluation {
    i32 *unsettled;
    i64 *cost, *supporter, *settled_sum, *heap, *offered_atoms, *level_first, *next_offer,
        *level_last, *plan, *helpful, *marked_atoms, *stack, *targets, *found;
    u8 *chosen, *marked, *unaccepted, *needed;
};

static int holds(const u8 *state, i64 atom) { return (state[atom >> 3] >> (atom & 7)) & 1; }

static int all_hold(const u8 *state, const i64 *atoms, i64 start, i64 end) {
    for (i64 position = start; position < end; position++)
        if (!holds(state, atoms[position])) return 0;
    return 1;
}

static int none_holds(const u8 *state, const i64 *atoms, i64 start, i64 end) {
    for (i64 position = start; position < end; position++)
        if (holds(state, atoms[position])) return 0;
    return 1;
}

static i64 heap_push(i64 *heap, i64 size, i64 key) {
    i64 position = size;
    while (position > 0) {
        i64 parent = (position - 1) >> 1;
        if (heap[parent] <= key) break;
        heap[position] = heap[parent];
        position = parent;
    }
    heap[position] = key;
    return size + 1;
}

static i64 heap_pop(i64 *heap, i64 size) {
    size -= 1;
    i64 last = heap[size], position = 0, child = 1;
    while (child < size) {
        if (child + 1 < size && heap[child + 1] < heap[child]) child += 1;
        if (heap[child] >= last) break;
        heap[position] = heap[child];
        position = child;
        child = 2 * position + 1;
    }
    heap[position] = last;
    return size;
}

/* Offer `sequence` (an atom at `cost`) to its bucket, or to the heap above the buckets. */
static void offer_atom(const struct GreedyTask *t, struct Evaluation *e, i64 *top, i64 *size, i64 sequence,
                       i64 cost) {
    if (cost < t->bucket_levels) {
        while (*top < cost) {
            *top += 1;
            e->level_first[*top] = -1;
        }
        e->next_offer[sequence] = -1;
        if (e->level_first[cost] < 0) e->level_first[cost] = sequence;
        else e->next_offer[e->level_last[cost]] = sequence;
        e->level_last[cost] = sequence;
    } else {
        *size = heap_push(e->heap, *size, (cost << SEQUENCE_BITS) | sequence);
    }
}

/* h_add's costs and best supporters from `state` (relaxed_kernel.additive_exploration); 0 if the goal is
   relaxed-unreachable. */
static int additive_exploration(const struct GreedyTask *t, struct Evaluation *e, const u8 *state) {
    i64 *cost = e->cost, *supporter = e->supporter;
    for (i64 atom = 0; atom < t->n_atoms; atom++) {
        cost[atom] = UNREACHED;
        supporter[atom] = -1;
    }
    memcpy(e->unsettled, t->precondition_counts, (size_t)t->n_actions * sizeof(i32));
    memset(e->settled_sum, 0, (size_t)t->n_actions * sizeof(i64));
    i64 top = -1, size = 0, sequence = 0;
    for (i64 atom = 0; atom < t->n_atoms; atom++) {
        if (holds(state, atom)) {
            cost[atom] = 0;
            e->offered_atoms[sequence] = atom;
            offer_atom(t, e, &top, &size, sequence, 0);
            sequence++;
        }
    }
    for (i64 k = 0; k < t->n_free_actions; k++) {
        i64 action = t->free_actions[k];
        for (i64 position = t->add_start[action]; position < t->add_start[action + 1]; position++) {
            i64 atom = t->adds[position];
            if (cost[atom] > 1) {
                cost[atom] = 1;
                supporter[atom] = action;
                e->offered_atoms[sequence] = atom;
                offer_atom(t, e, &top, &size, sequence, 1);
                sequence++;
            }
        }
    }
    i64 level = 0;
    for (;;) {
        int bucketed = level <= top;
        i64 offer = bucketed ? e->level_first[level] : -1;
        for (;;) {
            i64 atom;
            if (bucketed) {
                if (offer < 0) break;
                atom = e->offered_atoms[offer];
                offer = e->next_offer[offer];
            } else {
                if (size == 0 || (e->heap[0] >> SEQUENCE_BITS) != level) break;
                atom = e->offered_atoms[e->heap[0] & ((((i64)1) << SEQUENCE_BITS) - 1)];
                size = heap_pop(e->heap, size);
            }
            if (cost[atom] != level) continue; /* offered again at a lower cost, and settled then */
            for (i64 user = t->users_start[atom]; user < t->users_start[atom + 1]; user++) {
                i64 action = t->users[user];
                e->unsettled[action] -= 1;
                e->settled_sum[action] += level;
                if (e->unsettled[action] == 0) {
                    i64 value = e->settled_sum[action] + 1;
                    for (i64 position = t->add_start[action]; position < t->add_start[action + 1]; position++) {
                        i64 added = t->adds[position];
                        if (value < cost[added]) {
                            cost[added] = value;
                            supporter[added] = action;
                            e->offered_atoms[sequence] = added;
                            offer_atom(t, e, &top, &size, sequence, value);
                            sequence++;
                        }
                    }
                }
            }
        }
        int reached = 1;
        for (i64 k = 0; k < t->n_goal_ids; k++) {
            if (cost[t->goal_ids[k]] > level) {
                reached = 0;
                break;
            }
        }
        if (reached) return 1;
        level += 1;
        while (level <= top && e->level_first[level] < 0) level += 1;
        if (level > top) {
            if (size == 0) return 0;
            level = e->heap[0] >> SEQUENCE_BITS;
        }
    }
}

/* The best supporters' relaxed plan for `targets` and its actions applicable in `state`
   (relaxed_kernel.supported_plan): the plan's length; the applicable ones in e->helpful, their count in
   *applicable. */
static i64 supported_plan(const struct GreedyTask *t, struct Evaluation *e, const u8 *state, const i64 *targets,
                          i64 n_targets, i64 *applicable) {
    i64 depth = 0, length = 0, touched = 0;
    for (i64 k = 0; k < n_targets; k++) e->stack[depth++] = targets[k];
    while (depth > 0) {
        i64 atom = e->stack[--depth];
        if (e->marked[atom] || e->cost[atom] == 0) continue; /* handled already, or true in the state */
        e->marked[atom] = 1;
        e->marked_atoms[touched++] = atom;
        i64 action = e->supporter[atom];
        if (!e->chosen[action]) {
            e->chosen[action] = 1;
            e->plan[length++] = action;
            for (i64 position = t->pre_start[action]; position < t->pre_start[action + 1]; position++)
                e->stack[depth++] = t->pres[position];
        }
    }
    i64 count = 0;
    for (i64 index = 0; index < length; index++) {
        i64 action = e->plan[index];
        e->chosen[action] = 0;
        if (all_hold(state, t->pres, t->pre_start[action], t->pre_start[action + 1])) e->helpful[count++] = action;
    }
    for (i64 index = 0; index < touched; index++) e->marked[e->marked_atoms[index]] = 0;
    *applicable = count;
    return length;
}

/* The applicable actions achieving one of `targets` (relaxed_kernel.applicable_achievers), into e->found. */
static i64 applicable_achievers(const struct GreedyTask *t, struct Evaluation *e, const u8 *state,
                                const i64 *targets, i64 n_targets) {
    i64 count = 0;
    for (i64 k = 0; k < n_targets; k++) {
        i64 target = targets[k];
        for (i64 position = t->achievers_start[target]; position < t->achievers_start[target + 1]; position++) {
            i64 action = t->achievers[position];
            if (all_hold(state, t->pres, t->pre_start[action], t->pre_start[action + 1]) &&
                none_holds(state, t->negs, t->neg_start[action], t->neg_start[action + 1]))
                e->found[count++] = action;
        }
    }
    return count;
}

/* h_LM and the landmarks to reach next into e->targets, their count in *count
   (relaxed_kernel.landmark_count). */
static i64 landmark_count(const struct GreedyTask *t, struct Evaluation *e, const u8 *state, const u8 *accepted,
                          i64 *count) {
    i64 bytes = t->state_bytes;
    memset(e->unaccepted, 0, (size_t)bytes);
    memcpy(e->needed, t->landmark_goal, (size_t)bytes);
    i64 h = 0;
    for (i64 k = 0; k < t->n_landmarks; k++) {
        i64 atom = t->landmark_atoms[k];
        if (!holds(accepted, atom)) {
            e->unaccepted[atom >> 3] |= (u8)(1 << (atom & 7));
            const u8 *row = t->greedy_necessary + k * bytes;
            for (i64 index = 0; index < bytes; index++) e->needed[index] |= row[index];
            h++;
        }
    }
    i64 found = 0;
    for (i64 k = 0; k < t->n_landmarks; k++) {
        i64 atom = t->landmark_atoms[k];
        if (holds(e->unaccepted, atom)) {
            const u8 *row = t->natural + k * bytes;
            int free = 1;
            for (i64 index = 0; index < bytes; index++) {
                if (row[index] & e->unaccepted[index]) {
                    free = 0;
                    break;
                }
            }
            if (free) e->targets[found++] = atom;
        } else if (!holds(state, atom) && holds(e->needed, atom)) {
            h++; /* accepted, false now, and needed again */
            e->targets[found++] = atom;
        }
    }
    *count = found;
    return h;
}

/* LandmarkEvaluator's evaluation (greedy_kernel._evaluate): h_FF into *h_ff (-1 at a dead end) and h_LM
   into *h_landmarks; the preferred operators get preferred_stamp[action] = stamp. */
static void evaluate(const struct GreedyTask *t, struct Evaluation *e, const u8 *state, const u8 *accepted,
                     i64 stamp, i64 *preferred_stamp, i64 *h_ff, i64 *h_landmarks) {
    *h_landmarks = 0;
    if (!additive_exploration(t, e, state)) {
        *h_ff = -1;
        *h_landmarks = -1;
        return;
    }
    i64 applicable;
    *h_ff = supported_plan(t, e, state, t->goal_ids, t->n_goal_ids, &applicable);
    for (i64 index = 0; index < applicable; index++) preferred_stamp[e->helpful[index]] = stamp;
    if (!t->landmarks_used) return;
    i64 count;
    *h_landmarks = landmark_count(t, e, state, accepted, &count);
    if (!t->landmark_preferred) return;
    i64 achieving = applicable_achievers(t, e, state, e->targets, count);
    for (i64 index = 0; index < achieving; index++) preferred_stamp[e->found[index]] = stamp;
    if (achieving == 0 && count > 0) { /* towards the nearest landmarks to reach next */
        i64 nearest = UNREACHED;
        for (i64 index = 0; index < count; index++)
            if (e->cost[e->targets[index]] < nearest) nearest = e->cost[e->targets[index]];
        if (nearest != UNREACHED) {
            i64 kept = 0;
            for (i64 index = 0; index < count; index++)
                if (e->cost[e->targets[index]] == nearest) e->targets[kept++] = e->targets[index];
            supported_plan(t, e, state, e->targets, kept, &applicable);
            for (i64 index = 0; index < applicable; index++) preferred_stamp[e->helpful[index]] = stamp;
        }
    }
}

/* LandmarkCount.accepted_after (accepted_at_start at the root) into `accepted`. */
static void accept(const struct GreedyTask *t, const u8 *state, const u8 *parent_accepted, u8 *accepted,
                   int at_root) {
    i64 bytes = t->state_bytes;
    memmove(accepted, parent_accepted, (size_t)bytes);
    for (i64 k = 0; k < t->n_landmarks; k++) {
        i64 atom = t->landmark_atoms[k];
        if (!holds(state, atom) || holds(parent_accepted, atom)) continue;
        int free = 1;
        if (!at_root) {
            const u8 *row = t->natural + k * bytes;
            for (i64 index = 0; index < bytes; index++) {
                if (row[index] & (u8)(255 - parent_accepted[index])) {
                    free = 0;
                    break;
                }
            }
        }
        if (free) accepted[atom >> 3] |= (u8)(1 << (atom & 7));
    }
}

static void apply(const struct GreedyTask *t, const u8 *state, i64 action, u8 *child) {
    memcpy(child, state, (size_t)t->state_bytes);
    for (i64 position = t->delete_start[action]; position < t->delete_start[action + 1]; position++) {
        i64 atom = t->deletes[position];
        child[atom >> 3] &= (u8)(255 - (1 << (atom & 7)));
    }
    for (i64 position = t->add_start[action]; position < t->add_start[action + 1]; position++) {
        i64 atom = t->adds[position];
        child[atom >> 3] |= (u8)(1 << (atom & 7));
    }
}

/* The applicable actions in Task.successor_indices' order into `out`; their count. */
static i64 applicable_actions(const struct GreedyTask *t, const u8 *state, i64 *out) {
    i64 count = 0;
    for (i64 k = 0; k < t->n_unconditional; k++) {
        i64 action = t->unconditional[k];
        if (none_holds(state, t->negs, t->neg_start[action], t->neg_start[action + 1])) out[count++] = action;
    }
    for (i64 atom = 0; atom < t->n_atoms; atom++) {
        if (t->key_start[atom] == t->key_start[atom + 1] || !holds(state, atom)) continue;
        for (i64 position = t->key_start[atom]; position < t->key_start[atom + 1]; position++) {
            i64 action = t->key_actions[position];
            if (all_hold(state, t->pres, t->pre_start[action], t->pre_start[action + 1]) &&
                none_holds(state, t->negs, t->neg_start[action], t->neg_start[action + 1]))
                out[count++] = action;
        }
    }
    return count;
}

static i64 state_hash(const u8 *state, i64 bytes) { /* FNV-1a */
    uint64_t value = 14695981039346656037ULL;
    for (i64 index = 0; index < bytes; index++) value = (value ^ state[index]) * 1099511628211ULL;
    return (i64)(value & 0x7FFFFFFFFFFFFFFFULL);
}

/* The evaluated states: rows, their accepted landmarks, parents, actions and hashes, and the hash table. */
struct Rows {
    i64 bytes, count, capacity, table_size;
    u8 *states, *accepted;
    i64 *parents, *actions, *hashes, *table;
};

/* The slot of `state` in the table, or of the empty slot where it belongs. */
static i64 find_slot(const struct Rows *r, const u8 *state, i64 value) {
    i64 mask = r->table_size - 1, slot = value & mask;
    for (;;) {
        i64 row = r->table[slot];
        if (row < 0) return slot;
        if (r->hashes[row] == value && memcmp(r->states + row * r->bytes, state, (size_t)r->bytes) == 0) return slot;
        slot = (slot + 1) & mask;
    }
}

static int grow_rows(struct Rows *r) {
    i64 capacity = 2 * r->capacity;
    u8 *states = realloc(r->states, (size_t)(capacity * r->bytes));
    if (states) r->states = states;
    u8 *accepted = realloc(r->accepted, (size_t)(capacity * r->bytes));
    if (accepted) r->accepted = accepted;
    i64 *parents = realloc(r->parents, (size_t)capacity * sizeof(i64));
    if (parents) r->parents = parents;
    i64 *actions = realloc(r->actions, (size_t)capacity * sizeof(i64));
    if (actions) r->actions = actions;
    i64 *hashes = realloc(r->hashes, (size_t)capacity * sizeof(i64));
    if (hashes) r->hashes = hashes;
    i64 *table = malloc((size_t)(2 * capacity) * sizeof(i64));
    if (!states || !accepted || !parents || !actions || !hashes || !table) {
        free(table);
        return 0;
    }
    free(r->table);
    r->table = table;
    r->capacity = capacity;
    r->table_size = 2 * capacity;
    for (i64 slot = 0; slot < r->table_size; slot++) r->table[slot] = -1;
    for (i64 row = 0; row < r->count; row++) r->table[find_slot(r, r->states + row * r->bytes, r->hashes[row])] = row;
    return 1;
}

/* The queued entries ((parent row, action) pairs) and one heap of keys h << ORDER_BITS | entry per queue. */
struct Queues {
    i64 n, capacity, count;
    i64 *parents, *actions, *sizes, *priorities;
    i64 *heaps[5];
};

static int grow_queues(struct Queues *q) {
    i64 capacity = 2 * q->capacity;
    i64 *parents = realloc(q->parents, (size_t)capacity * sizeof(i64));
    if (!parents) return 0;
    q->parents = parents;
    i64 *actions = realloc(q->actions, (size_t)capacity * sizeof(i64));
    if (!actions) return 0;
    q->actions = actions;
    for (i64 queue = 0; queue < q->n; queue++) {
        i64 *heap = realloc(q->heaps[queue], (size_t)capacity * sizeof(i64));
        if (!heap) return 0;
        q->heaps[queue] = heap;
    }
    q->capacity = capacity;
    return 1;
}

static void push(struct Queues *q, i64 queue, i64 key) { q->sizes[queue] = heap_push(q->heaps[queue], q->sizes[queue], key); }

static double monotonic_seconds(void) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + (double)now.tv_nsec * 1e-9;
}

static void *zeroed(i64 count, size_t size) { return calloc((size_t)(count > 0 ? count : 1), size); }

void greedy_result_free(struct GreedyResult *result) {
    free(result->parents);
    free(result->actions);
    result->parents = result->actions = NULL;
}

/* One search from t->root, its state kept between turns so that several can take turns (greedy_portfolio). */
struct Search {
    const struct GreedyTask *t;
    struct GreedySettings s;
    struct Evaluation e;
    struct Rows r;
    struct Queues q;
    i64 *preferred_stamp, *applicable;
    u8 *child, *seen, *root_accepted;
    i64 outcome, goal_row, expanded, generated, evaluated, best_ff, best_landmarks, stamp;
};

static void search_free(struct Search *x) {
    struct Evaluation *e = &x->e;
    free(e->cost); free(e->supporter); free(e->unsettled); free(e->settled_sum); free(e->heap);
    free(e->offered_atoms); free(e->next_offer); free(e->level_first); free(e->level_last); free(e->plan);
    free(e->helpful); free(e->marked_atoms); free(e->stack); free(e->targets); free(e->found); free(e->chosen);
    free(e->marked); free(e->unaccepted); free(e->needed);
    free(x->preferred_stamp); free(x->applicable); free(x->child); free(x->seen); free(x->root_accepted);
    free(x->r.states); free(x->r.accepted); free(x->r.hashes); free(x->r.table); free(x->r.parents);
    free(x->r.actions);
    free(x->q.parents); free(x->q.actions); free(x->q.sizes); free(x->q.priorities);
    for (i64 queue = 0; queue < x->q.n; queue++) free(x->q.heaps[queue]);
    free(x);
}

/* A search with its root evaluated and queued; NULL when memory ran out. */
static struct Search *search_new(const struct GreedyTask *t, const struct GreedySettings *s) {
    struct Search *x = calloc(1, sizeof(struct Search));
    if (!x) return NULL;
    i64 bytes = t->state_bytes, n_atoms = t->n_atoms, n_actions = t->n_actions;
    i64 offers = n_atoms + t->add_start[n_actions] + 1;
    x->t = t;
    x->s = *s;
    x->e = (struct Evaluation){
        .cost = zeroed(n_atoms, sizeof(i64)), .supporter = zeroed(n_atoms, sizeof(i64)),
        .unsettled = zeroed(n_actions, sizeof(i32)), .settled_sum = zeroed(n_actions, sizeof(i64)),
        .heap = zeroed(offers, sizeof(i64)), .offered_atoms = zeroed(offers, sizeof(i64)),
        .next_offer = zeroed(offers, sizeof(i64)), .level_first = zeroed(t->bucket_levels, sizeof(i64)),
        .level_last = zeroed(t->bucket_levels, sizeof(i64)), .plan = zeroed(n_actions, sizeof(i64)),
        .helpful = zeroed(n_actions, sizeof(i64)), .marked_atoms = zeroed(n_atoms, sizeof(i64)),
        .stack = zeroed(n_atoms + t->pre_start[n_actions] + 1, sizeof(i64)),
        .targets = zeroed(t->n_landmarks + 1, sizeof(i64)),
        .found = zeroed(t->achievers_start[n_atoms] + 1, sizeof(i64)),
        .chosen = zeroed(n_actions, 1), .marked = zeroed(n_atoms, 1),
        .unaccepted = zeroed(bytes, 1), .needed = zeroed(bytes, 1),
    };
    struct Evaluation *e = &x->e;
    x->preferred_stamp = zeroed(n_actions, sizeof(i64));
    x->applicable = zeroed(n_actions, sizeof(i64));
    x->child = zeroed(bytes, 1);
    x->seen = zeroed(bytes, 1);
    x->root_accepted = zeroed(bytes, 1);
    struct Rows *r = &x->r;
    *r = (struct Rows){.bytes = bytes, .count = 0, .capacity = 1024, .table_size = 2048};
    r->states = zeroed(r->capacity * bytes, 1);
    r->accepted = zeroed(r->capacity * bytes, 1);
    r->parents = zeroed(r->capacity, sizeof(i64));
    r->actions = zeroed(r->capacity, sizeof(i64));
    r->hashes = zeroed(r->capacity, sizeof(i64));
    r->table = zeroed(r->table_size, sizeof(i64));
    struct Queues *q = &x->q;
    *q = (struct Queues){.n = 2 * s->heuristics + 1, .capacity = 4096, .count = 0};
    q->parents = zeroed(q->capacity, sizeof(i64));
    q->actions = zeroed(q->capacity, sizeof(i64));
    q->sizes = zeroed(q->n, sizeof(i64));
    q->priorities = zeroed(q->n, sizeof(i64));
    int ready = e->cost && e->supporter && e->unsettled && e->settled_sum && e->heap && e->offered_atoms &&
                e->next_offer && e->level_first && e->level_last && e->plan && e->helpful && e->marked_atoms &&
                e->stack && e->targets && e->found && e->chosen && e->marked && e->unaccepted && e->needed &&
                x->preferred_stamp && x->applicable && x->child && x->seen && x->root_accepted && r->states &&
                r->accepted && r->parents && r->actions && r->hashes && r->table && q->parents && q->actions &&
                q->sizes && q->priorities;
    for (i64 queue = 0; queue < q->n; queue++) {
        q->heaps[queue] = zeroed(q->capacity, sizeof(i64));
        ready = ready && q->heaps[queue];
    }
    if (!ready) {
        search_free(x);
        return NULL;
    }
    for (i64 slot = 0; slot < r->table_size; slot++) r->table[slot] = -1;
    for (i64 action = 0; action < n_actions; action++) x->preferred_stamp[action] = -1;
    if (s->novelty) memcpy(x->seen, t->root, (size_t)bytes);
    else memset(x->seen, 255, (size_t)bytes);
    accept(t, t->root, x->root_accepted, x->root_accepted, 1);
    evaluate(t, e, t->root, x->root_accepted, 0, x->preferred_stamp, &x->best_ff, &x->best_landmarks);
    q->parents[0] = -1;
    q->actions[0] = -1;
    push(q, 0, x->best_ff << ORDER_BITS);
    if (s->heuristics == 2) push(q, 2, x->best_landmarks << ORDER_BITS);
    q->count = 1;
    x->outcome = RUNNING;
    x->goal_row = -1;
    x->generated = 1;
    return x;
}

/* Takes the search on until it ends (its outcome) or has evaluated `until_evaluated` states (RUNNING),
   taking the deadline and x->s.max_expansions as its budget. */
static i64 search_run(struct Search *x, i64 until_evaluated) {
    const struct GreedyTask *t = x->t;
    const struct GreedySettings *s = &x->s;
    struct Evaluation *e = &x->e;
    struct Rows *r = &x->r;
    struct Queues *q = &x->q;
    i64 bytes = t->state_bytes, check_at = x->expanded;
    u8 *child = x->child;
    while (x->evaluated < until_evaluated) {
        i64 queued = 0;
        for (i64 queue = 0; queue < q->n; queue++) queued += q->sizes[queue];
        if (queued == 0) return x->outcome = UNSOLVABLE;
        if (x->expanded >= check_at) {
            if ((s->max_expansions >= 0 && x->expanded >= s->max_expansions) ||
                (s->deadline >= 0.0 && monotonic_seconds() > s->deadline))
                return x->outcome = OUT_OF_BUDGET;
            check_at = s->deadline >= 0.0 ? x->expanded + CLOCK_EVERY : INT64_MAX;
            if (s->max_expansions >= 0 && s->max_expansions < check_at) check_at = s->max_expansions;
        }
        i64 side = -1;
        for (i64 queue = 0; queue < q->n; queue++)
            if (q->sizes[queue] > 0 && (side < 0 || q->priorities[queue] < q->priorities[side])) side = queue;
        q->priorities[side] += 1;
        i64 entry = q->heaps[side][0] & ((((i64)1) << ORDER_BITS) - 1);
        q->sizes[side] = heap_pop(q->heaps[side], q->sizes[side]);
        i64 parent = q->parents[entry], action = q->actions[entry];
        if (parent < 0) memcpy(child, t->root, (size_t)bytes);
        else apply(t, r->states + parent * bytes, action, child);
        i64 value = state_hash(child, bytes);
        i64 slot = find_slot(r, child, value);
        if (r->table[slot] >= 0) continue; /* evaluated already */
        if (r->count == r->capacity) {
            if (!grow_rows(r)) return x->outcome = OUT_OF_MEMORY;
            slot = find_slot(r, child, value);
        }
        i64 node = r->count++;
        r->table[slot] = node;
        u8 *state = r->states + node * bytes, *accepted = r->accepted + node * bytes;
        memcpy(state, child, (size_t)bytes);
        r->parents[node] = parent;
        r->actions[node] = action;
        r->hashes[node] = value;
        if (parent < 0) memcpy(accepted, x->root_accepted, (size_t)bytes);
        else accept(t, state, r->accepted + parent * bytes, accepted, 0);
        x->stamp += 1;
        i64 h_ff, h_landmarks;
        evaluate(t, e, state, accepted, x->stamp, x->preferred_stamp, &h_ff, &h_landmarks);
        x->evaluated += 1;
        if (h_ff < 0) continue;
        int is_goal = 1;
        for (i64 index = 0; index < bytes; index++) {
            if ((state[index] & t->goal[index]) != t->goal[index] || (state[index] & t->goal_neg[index])) {
                is_goal = 0;
                break;
            }
        }
        if (is_goal) {
            x->goal_row = node;
            return x->outcome = SOLVED;
        }
        int improved = h_ff < x->best_ff || (s->heuristics == 2 && h_landmarks < x->best_landmarks);
        if (h_ff < x->best_ff) x->best_ff = h_ff;
        if (h_landmarks < x->best_landmarks) x->best_landmarks = h_landmarks;
        if (improved) {
            for (i64 queue = 1; queue < q->n; queue += 2) q->priorities[queue] -= s->boost; /* the preferred queues */
            q->priorities[q->n - 1] -= s->boost;                                            /* the novel queue */
        }
        x->expanded += 1;
        i64 count = applicable_actions(t, state, x->applicable);
        for (i64 index = 0; index < count; index++) {
            i64 successor = x->applicable[index];
            apply(t, state, successor, child);
            if (r->table[find_slot(r, child, state_hash(child, bytes))] >= 0) continue;
            x->generated += 1;
            int novel = 0;
            if (s->novelty) {
                for (i64 byte = 0; byte < bytes; byte++) {
                    if (child[byte] & (u8)(255 - x->seen[byte])) {
                        novel = 1;
                        break;
                    }
                }
                if (novel)
                    for (i64 byte = 0; byte < bytes; byte++) x->seen[byte] |= child[byte];
            }
            if (q->count == q->capacity && !grow_queues(q)) return x->outcome = OUT_OF_MEMORY;
            i64 order = q->count++;
            q->parents[order] = node;
            q->actions[order] = successor;
            int preferred = x->preferred_stamp[successor] == x->stamp;
            push(q, 0, h_ff << ORDER_BITS | order);
            if (preferred) push(q, 1, h_ff << ORDER_BITS | order);
            if (s->heuristics == 2) {
                push(q, 2, h_landmarks << ORDER_BITS | order);
                if (preferred) push(q, 3, h_landmarks << ORDER_BITS | order);
            }
            if (novel) push(q, q->n - 1, h_ff << ORDER_BITS | order);
        }
    }
    return RUNNING;
}

/* Several searches of one task taking turns (alternating_greedy's portfolio): the first alone until it
   has evaluated `alone` states, then each in turn for `turn` evaluations, in the order given, until one
   ends. Every search is complete, so one that runs out of states proves the task unsolvable. The counts
   are the sums over the searches; the rows those of the search that ended (*ended: its index). Each
   search's max_expansions is what the others have left of `settings[0].max_expansions`. */
i64 greedy_portfolio(const struct GreedyTask *const *tasks, const struct GreedySettings *settings, i64 n,
                     i64 alone, i64 turn, struct GreedyResult *result) {
    struct Search *searches[PORTFOLIO_MAX];
    i64 started = 0, outcome = OUT_OF_MEMORY, winner = 0, total_limit = settings[0].max_expansions;
    if (n < 1 || n > PORTFOLIO_MAX) return OUT_OF_MEMORY; /* the caller keeps to PORTFOLIO_MAX */
    for (i64 k = 0; k < n; k++) searches[k] = NULL;
    searches[0] = search_new(tasks[0], &settings[0]);
    if (!searches[0]) goto done;
    started = 1;
    for (i64 round = 0;; round++) {
        for (i64 k = 0; k < n; k++) {
            if (k >= started) {
                if (round == 0) break; /* the first alone in the first round */
                searches[k] = search_new(tasks[k], &settings[k]);
                if (!searches[k]) goto done;
                started = k + 1;
            }
            struct Search *x = searches[k];
            if (total_limit >= 0) { /* what the others have not expanded */
                i64 others = 0;
                for (i64 j = 0; j < started; j++)
                    if (j != k) others += searches[j]->expanded;
                x->s.max_expansions = total_limit - others;
            }
            outcome = search_run(x, round == 0 ? alone : x->evaluated + turn);
            if (outcome != RUNNING) {
                winner = k;
                goto done;
            }
        }
    }
done:
    result->outcome = outcome;
    result->goal_row = -1;
    result->expanded = result->generated = result->evaluated = result->n_rows = 0;
    result->parents = result->actions = NULL;
    for (i64 k = 0; k < started; k++) {
        result->expanded += searches[k]->expanded;
        result->generated += searches[k]->generated;
        result->evaluated += searches[k]->evaluated;
    }
    if (started > winner && searches[winner]) {
        struct Search *x = searches[winner];
        result->goal_row = x->goal_row;
        result->n_rows = x->r.count;
        result->parents = x->r.parents; /* handed to the result: greedy_result_free frees them */
        result->actions = x->r.actions;
        x->r.parents = x->r.actions = NULL;
    }
    for (i64 k = 0; k < started; k++) search_free(searches[k]);
    return outcome;
}
