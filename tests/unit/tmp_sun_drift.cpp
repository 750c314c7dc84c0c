#include <gtest/gtest.h>
#include <cstdio>
#include "core/stopwatch.h"
#include "luxel/animation.h"
#include "luxel/bench.h"
#include "luxel/import.h"
#include "luxel/session.h"
namespace luxel {
TEST(TmpSunDrift, Measure) {
  const Scene base = loadSceneFile("/work/main/bench/scenes/sibenik-sun.json");
  SessionOptions o; o.solve.method = "hierarchical";
  SessionOptions acc = o; acc.solve.settings.set("error", 2e-5); acc.solve.settings.set("emitter-points", 4);
  Session s(base, DiscretiseOptions{}, o);
  s.solve();
  for (int k = 1; k <= 60; ++k) {
    s.setLights(lightsAt(base, k / 30.0));
    const Solution c = s.solve();
    if (k != 1 && k != 10 && k != 30 && k != 40 && k != 50 && k != 60) continue;
    Session f(base, DiscretiseOptions{}, o);
    f.setLights(lightsAt(base, k / 30.0));
    const Solution fr = f.solve();
    Session r(base, DiscretiseOptions{}, acc);
    r.setLights(lightsAt(base, k / 30.0));
    const Solution ref = r.solve();
    std::printf("frame %d: followed %.4f fresh %.4f (changes followed %llu)\n", k,
      bench::normalisedRmsError(s.surfaces(), c.radiosity, ref.radiosity),
      bench::normalisedRmsError(s.surfaces(), fr.radiosity, ref.radiosity), (unsigned long long)c.stats.redistributions);
    std::fflush(stdout);
  }
}
}
