/* A hashed uniform grid over a store of records on the device, built by counting sort (SmallVCM's
 * hashgrid.hxx: count per cell, prefix sum, scatter), each cell's run then sorted by the records'
 * keys so that a query sums a cell in one order whatever order the atomics stored it in.
 * Photon mapping's gather (photon_gather.cl) and vertex merging (vcm.cl) include it. A record
 * starts with its position (3 floats) and has its key — a path index and a depth, two ints in
 * float bits — at KASHA_PHOTON_INDEX and KASHA_PHOTON_DEPTH; KASHA_RECORD_FLOATS is its stride. */
#include "shared/launch_range.h"
#include "shared/photon_layout.h"

#ifndef KASHA_RECORD_FLOATS
#define KASHA_RECORD_FLOATS KASHA_PHOTON_FLOATS(KASHA_BINS, KASHA_SCATTERING)
#endif
/* Whether a record goes in the grid (vertex merging leaves out the vertices no merge may use);
 * the others get no cell (KASHA_NO_CELL) and no slot. */
#ifndef KASHA_RECORD_IN_GRID
#define KASHA_RECORD_IN_GRID(r) true
#endif
#define KASHA_NO_CELL 0xffffffffu

/* The gather's tests must round as nanoflann's on the host does (the two are compared). */
#pragma OPENCL FP_CONTRACT OFF

inline int3 grid_cell(float3 x, float inv_cell) {
  return convert_int3_sat_rtn(x * inv_cell);
}

inline uint grid_hash(int3 c, uint mask) {
  return ((uint)c.x * 73856093u ^ (uint)c.y * 19349663u ^ (uint)c.z * 83492791u) & mask;
}

inline float3 record_position(const __global float* r) {
  return (float3)(r[0], r[1], r[2]);
}

/* Per photon: its cell's hash, counted. */
__kernel void grid_count(__global const float* store, __global const float* cell, uint mask,
                         __global int* cell_count, __global uint* photon_cell, KASHA_LAUNCH_RANGE) {
  int i = launch_item(item_first);
  if (i >= item_end) return;
  const __global float* r = store + (long)i * KASHA_RECORD_FLOATS;
  if (!KASHA_RECORD_IN_GRID(r)) {
    photon_cell[i] = KASHA_NO_CELL;
    return;
  }
  uint h = grid_hash(grid_cell(record_position(r), cell[1]), mask);
  photon_cell[i] = h;
  atomic_inc(cell_count + h);
}

/* One work-group: cell_end[h] = Σ_{j<h} cell_count[j], each work item scanning a contiguous chunk
 * (the scatter then advances it to the cell's end). */
__kernel void grid_scan(__global const int* cell_count, int cells, __global int* cell_end, KASHA_LAUNCH_RANGE) {
  __local int total[256];
  int l = get_local_id(0), n = min((int)get_local_size(0), 256);
  int chunk = (cells + n - 1) / n;
  int first = min(l * chunk, cells), last = min(first + chunk, cells);
  int s = 0;
  if (l < n) {
    for (int j = first; j < last; ++j) s += cell_count[j];
    total[l] = s;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (l >= n) return;
  int offset = 0;
  for (int i = 0; i < l; ++i) offset += total[i];
  for (int j = first; j < last; ++j) {
    cell_end[j] = offset;
    offset += cell_count[j];
  }
}

/* Per photon: its index into its cell's run of the sorted array. */
__kernel void grid_scatter(__global const uint* photon_cell, __global int* cell_end, __global int* sorted,
                           KASHA_LAUNCH_RANGE) {
  int i = launch_item(item_first);
  if (i >= item_end) return;
  uint h = photon_cell[i];
  if (h != KASHA_NO_CELL) sorted[atomic_inc(cell_end + h)] = i;
}

/* Per sorted slot: its record's position and index (float bits), in the grid's order, for queries
 * that test many records' distances (vertex merging): they read these in runs rather than each
 * record where it lies in a store far larger than the caches. Run after grid_sort_cells; the
 * slots past the last cell's end (records left out of the grid) hold none. */
__kernel void grid_place(__global const float* store, __global const int* sorted, __global const int* cell_end,
                         uint mask, __global float4* placed, KASHA_LAUNCH_RANGE) {
  int i = launch_item(item_first);
  if (i >= item_end || i >= cell_end[mask]) return;
  int record = sorted[i];
  const __global float* r = store + (long)record * KASHA_RECORD_FLOATS;
  placed[i] = (float4)(r[0], r[1], r[2], as_float(record));
}

/* A stored photon's key: its index in the pass, then the bounce it was stored at. */
inline ulong record_key(const __global float* store, int record) {
  const __global float* r = store + (long)record * KASHA_RECORD_FLOATS;
  return (ulong)as_uint(r[KASHA_PHOTON_INDEX]) << 32 | as_uint(r[KASHA_PHOTON_DEPTH]);
}

/* Per hash cell: its run of `sorted` ordered by key (heap sort, in place), as the scatter's atomics
 * leave it in arrival order. A gather then sums each cell's photons in one order whatever the
 * launches and the device, so the same photons always give the same image, bit for bit. */
__kernel void grid_sort_cells(__global const float* store, __global const int* cell_count,
                              __global const int* cell_end, __global int* sorted, KASHA_LAUNCH_RANGE) {
  int h = launch_item(item_first);
  if (h >= item_end) return;
  int n = cell_count[h];
  if (n < 2) return;
  __global int* a = sorted + (cell_end[h] - n);
  /* Sift-down heap sort: a max-heap over [0, size), its root swapped to the end each round. */
  for (int start = n / 2 - 1, size = n; size > 1;) {
    int root;
    if (start >= 0) {
      root = start--;
    } else {
      --size;
      int t = a[0];
      a[0] = a[size];
      a[size] = t;
      root = 0;
    }
    for (;;) {
      int child = 2 * root + 1;
      if (child >= size) break;
      if (child + 1 < size && record_key(store, a[child + 1]) > record_key(store, a[child])) ++child;
      if (record_key(store, a[child]) <= record_key(store, a[root])) break;
      int t = a[root];
      a[root] = a[child];
      a[child] = t;
      root = child;
    }
  }
}

