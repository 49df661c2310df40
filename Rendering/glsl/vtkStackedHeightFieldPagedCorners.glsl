// Paged: the four corners of cell c of the leaf whose page strataLeafPage set (its slot and
// first point), read from the tile's own texels.
vec4 strataCellCorners(int layer, ivec2 c)
{
  ivec2 q = c - gPageBase;
  return vec4(strataTexel(gPageSlot, q), strataTexel(gPageSlot, q + ivec2(1, 0)),
    strataTexel(gPageSlot, q + ivec2(0, 1)), strataTexel(gPageSlot, q + ivec2(1, 1)));
}
