// Back to front over the lattice steps k of [tEnter, tExit], each step clipped to the
  // fragment; no early termination.
  float kb = ceil(tExit / dt - phase);
  //STRATA::Start::Impl
  for (int it = 0; it < 1048576; ++it)
  {
    float b = min((kb + phase) * dt, tExit);
    float a = max((kb - 1.0 + phase) * dt, tEnter);
    if (b <= tEnter)
    {
      break;
    }
    //STRATA::Layers::Impl
    //STRATA::Skip::Impl
    if (b > a)
    {
      //STRATA::Step::Impl
      if (c.a > 0.0)
      {
        tFirst = max(a - dt, tEnter);
      }
      //STRATA::Probe::Impl
      acc = c + (1.0 - c.a) * acc;
    }
    kb -= 1.0;
  }
  //STRATA::LayersAfter::Impl
