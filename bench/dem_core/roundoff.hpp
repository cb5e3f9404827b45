#pragma once
// How much reorder_particles changes results (it changes round-off only; granular flow amplifies
// round-off chaotically): the docs/spec.md 2.2 s = 4 drum torque and the docs/spec.md 2.1 pellet compression
// curve, each run with and without reordering from the same prepared state.
namespace demfit::bench {

void print_reordering_roundoff(bool quick);

}  // namespace demfit::bench
