// Paged: the leaf's tile and the level its cells are walked in.
  lv = strataLeafPage(layer, cLo0);
  if (lv < 0)
  {
    return BIG; // an empty tile, or one without a slot: a hole
  }
