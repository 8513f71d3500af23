/* A max-priority queue of pixel indices, for the unwrapping and demodulation flood fills that
 * visit the most reliable pixel next. Both fills rely on the exact visiting order (ties included)
 * for reproducible maps, so there is one implementation of it. */
#ifndef BIREF_PIXEL_HEAP_H
#define BIREF_PIXEL_HEAP_H

#include <stddef.h>

typedef struct {
    float priority;
    int px;
} pixel_heap_item;

typedef struct {
    pixel_heap_item *a; /* caller-allocated, room for every push */
    size_t n;
} pixel_heap;

static inline void pixel_heap_push(pixel_heap *h, float priority, int px)
{
    size_t k = h->n++;
    while (k > 0) {
        size_t p = (k - 1) / 2;
        if (h->a[p].priority >= priority) break;
        h->a[k] = h->a[p];
        k = p;
    }
    h->a[k].priority = priority;
    h->a[k].px = px;
}

/* The item of highest priority; h->n must be > 0. */
static inline pixel_heap_item pixel_heap_pop(pixel_heap *h)
{
    pixel_heap_item top = h->a[0], last = h->a[--h->n];
    size_t k = 0;
    for (;;) {
        size_t c = 2 * k + 1;
        if (c >= h->n) break;
        if (c + 1 < h->n && h->a[c + 1].priority > h->a[c].priority) c++;
        if (h->a[c].priority <= last.priority) break;
        h->a[k] = h->a[c];
        k = c;
    }
    if (h->n) h->a[k] = last;
    return top;
}

#endif
