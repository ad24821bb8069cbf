// PBF, Algorithm 1 line 6 (Macklin & Mueller 2013): find each particle's neighbours once per
// substep, after the sort, and list them for the constraint iterations, which sum over the same
// neighbourhood twice per iteration. A grid walk visits ~200 candidates per particle in 3D of
// which ~30 are in range; a list visits those. The pairs within reach2 (the support and a skin)
// at the predicted positions, in grid-walk order; an iteration still tests each pair's distance
// at its current positions, so it sums what a grid walk would as long as no pair closes by more
// than the skin within the substep. Slot-major (slot k of particle i at k*list_stride + i), so a
// warp's loads of one slot are contiguous. A particle with more neighbours than its slots keeps
// its count, and the passes walk the grid for it instead. It also keeps x* for the velocity
// update (pred; copy_positions.comp's work, one dispatch fewer).
BUFFER_POS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_NLIST BUFFER_BLIST BUFFER_NCOUNT
BUFFER_PRED
uniform uint list_stride, fluid_cap, boundary_cap;
uniform float reach2;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec4 x4 = pos[i];
  pred[i] = x4;
  vec3 xi = x4.xyz;
  uint key = fkey[i];
  uint nf = 0u, nb = 0u;
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      if (dot(d, d) >= reach2) continue;
      if (nf < fluid_cap) nlist[nf * list_stride + i] = j;
      ++nf;
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec3 d = min_image(xi - bpos[j].xyz);
      if (dot(d, d) >= reach2) continue;
      if (nb < boundary_cap) blist[nb * list_stride + i] = j;
      ++nb;
    }
  }
  ncount[i] = uvec2(nf, nb);
}
