// Front to back over the lattice steps k of [tEnter, tExit], each step clipped to the
  // fragment; stops at the fragment's share of the termination opacity.
  float kk = floor(tEnter / dt - phase);
  //STRATA::Start::Impl
  //STRATA::Surfaces::Start
  for (int it = 0; it < 1048576; ++it)
  {
    float a = max((kk + phase) * dt, tEnter);
    float b = min((kk + 1.0 + phase) * dt, tExit);
    if (a >= tExit)
    {
      break;
    }
    //STRATA::Layers::Impl
    //STRATA::Skip::Impl
    //STRATA::Surfaces::Split
    if (b > a)
    {
      //STRATA::Step::Impl
      if (c.a > 0.0 && tFirst == tExit)
      {
        tFirst = max(a - dt, tEnter);
      }
      //STRATA::Probe::Impl
      acc += (1.0 - acc.a) * c;
      if (acc.a >= localStop)
      {
        break;
      }
    }
    //STRATA::Surfaces::Resume
    kk += 1.0;
  }
  //STRATA::LayersAfter::Impl
