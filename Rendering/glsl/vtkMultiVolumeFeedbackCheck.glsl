// Feedback: the cut level of brick b against the level the ray wants; the lacking brick that
// costs the ray most (transmittance in front times 2^(levels too coarse), at most 2^16) is
// kept, the nearer one on ties. `coarse` is 2^level of the node covering b (the atlas lookup's
// 1 / scale; huge for a transparent brick, 0 for a slotless one, which never counts).
if (gFeedbackRay)
  {
    //STRATA::Want::Impl
    float lack = coarse * exp2(-float(want));
    float score = lack > 1.0 ? gTransmittance * min(lack, 65536.0) : 0.0;
    bool better = score @better@ gLackScore && score > 0.0;
    gLackFound = gLackFound || better;
    gLackScore = better ? score : gLackScore;
    gLack = better ? ivec4(b, want) : gLack;
    gLackVolume = better ? @n@ : gLackVolume;
  }
