// Feedback: the cut level e.w of brick b against the level the ray wants; the lacking brick
// that costs the ray most (transmittance in front times 2^(levels too coarse)) is kept, the
// nearer one on ties.
if (gFeedbackRay)
  {
    //STRATA::Want::Impl
    float score = e.w != 65535u && e.w > uint(want) ? gTransmittance * exp2(float(min(int(e.w) - want, 16))) : 0.0;
    bool better = score @better@ gLackScore && score > 0.0;
    gLackFound = gLackFound || better;
    gLackScore = better ? score : gLackScore;
    gLack = better ? ivec4(b, want) : gLack;
    gLackVolume = better ? @n@ : gLackVolume;
  }
