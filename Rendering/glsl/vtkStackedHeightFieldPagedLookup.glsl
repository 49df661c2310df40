// Strata stacked height-field ray caster: the height lookup of paged horizons (virtual
// texture). Level-0 grid point p lies in level-0 tile p / S (S = B - 1, tiles share their
// border points); the page table names the resident tile of level l covering it (its atlas
// slot) and level l holds every 2^l-th point, so the height is level l interpolated
// bilinearly at p / 2^l; at level 0 it is a single fetch of the data itself. Tiles of
// different levels meet without cracks because the atlas holds them stitched: a finer tile's
// border texels lie on its coarser neighbour's border (strata::HeightFieldPager), so this lookup and
// the layer's search, which walks each tile's own texels, see one surface.
uniform sampler2DArray uAtlas;      // one B x B tile per layer (slot)
uniform usampler2DArray uPageTable; // per level-0 tile and horizon: slot x, y, z and level
uniform int uPageStride;            // S = B - 1
uniform ivec2 uPageTiles;           // level-0 tiles per axis

float strataTexel(int slot, ivec2 q)
{
  return texelFetch(uAtlas, ivec3(q, slot), 0).r;
}

float strataHeight(int layer, ivec2 p)
{
  ivec2 tile = min(p / uPageStride, uPageTiles - 1);
  uvec4 entry = texelFetch(uPageTable, ivec3(tile, layer), 0);
  if (entry.w >= 65534u)
  {
    return 3.0e38; // empty or without a slot: a hole (the hole test rejects |h| >= 1e30)
  }
  int l = int(entry.w);
  int slot = int(entry.z);
  ivec2 q = (p >> l) - (tile >> l) * uPageStride;
  ivec2 r = p & ((1 << l) - 1);
  float h00 = strataTexel(slot, q);
  if (r.x == 0 && r.y == 0)
  {
    return h00;
  }
  float h10 = r.x > 0 ? strataTexel(slot, q + ivec2(1, 0)) : h00;
  float h01 = r.y > 0 ? strataTexel(slot, q + ivec2(0, 1)) : h00;
  float h11 = (r.x > 0 && r.y > 0) ? strataTexel(slot, q + ivec2(1, 1)) : (r.x > 0 ? h10 : h01);
  vec2 f = vec2(r) / float(1 << l);
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

// The page of the leaf whose first cell is `cell` (a leaf never straddles tiles): sets the
// slot and first point used by strataCellCorners and returns the level, -1 for a hole.
int gPageSlot = 0;
ivec2 gPageBase = ivec2(0);
int strataLeafPage(int layer, ivec2 cell)
{
  ivec2 tile = min(cell / uPageStride, uPageTiles - 1);
  uvec4 entry = texelFetch(uPageTable, ivec3(tile, layer), 0);
  if (entry.w >= 65534u)
  {
    return -1;
  }
  int l = int(entry.w);
  gPageSlot = int(entry.z);
  gPageBase = (tile >> l) * uPageStride;
  return l;
}
