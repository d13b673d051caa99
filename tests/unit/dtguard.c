/* dtguard.c - the step guard's limit against its definition (core/scene/dtguard.h): t_c =
 * pi / sqrt(Y / m_eff - (gamma_N / 2)^2) of the lightest pair, m_eff = m_min / 2 (two
 * equal disks), the limit k t_c per integrator capped by an absolute bound, computed
 * here from the formula for known Y, gamma_N and masses; and the check's three answers. */
#include <math.h>
#include <string.h>

#include "dtguard.h"
#include "params.h"
#include "testlib.h"

int main(void)
{
	const double pi = 3.14159265358979323846;
	/* m_min = 0.5 g, Y = 1e6 dyn/cm, gamma_N = 0: t_c = pi / sqrt(1e6 / 0.25) = pi / 2000 */
	double tc = 0, lim = dtguard_limit(INTEG_GEAR5, 1e6, 0, 0.5, &tc);
	CHECK_REL("dtguard.tc.undamped", tc, pi / 2000, 1e-15);
	CHECK_REL("dtguard.limit.gear5", lim, 0.15 * pi / 2000, 1e-15);
	lim = dtguard_limit(INTEG_GEAR4, 1e6, 0, 0.5, &tc);
	CHECK_REL("dtguard.limit.gear4", lim, 0.2 * pi / 2000, 1e-15);
	lim = dtguard_limit(INTEG_VERLET, 1e6, 0, 0.5, &tc);
	CHECK_REL("dtguard.limit.verlet", lim, 0.4 * pi / 2000, 1e-15);
	/* damped: gamma_N = 1000 1/s: w = sqrt(4e6 - 2.5e5) */
	dtguard_limit(INTEG_GEAR5, 1e6, 1000, 0.5, &tc);
	CHECK_REL("dtguard.tc.damped", tc, pi / sqrt(4e6 - 2.5e5), 1e-15);
	/* soft contacts: the absolute bounds (4e-4 s for Gear, 1.2e-3 s for Verlet) */
	lim = dtguard_limit(INTEG_GEAR5, 1e2, 0, 0.5, &tc);
	CHECK("dtguard.cap.gear5", lim == 4e-4, "limit %g", lim);
	lim = dtguard_limit(INTEG_VERLET, 1e2, 0, 0.5, &tc);
	CHECK("dtguard.cap.verlet", lim == 1.2e-3, "limit %g", lim);

	/* the check: refused beyond the limit, warned beyond half, silent below */
	sb_scene sc;
	params_defaults(&sc);
	sc.stiffness = 1e6;
	sc.gamma_n = 0;
	sc.integrator = INTEG_GEAR5;
	sc.dt_guard = 0;
	char warn[256];
	sb_err e = {0};
	sc.dt = 0.16 * pi / 2000;
	CHECK("dtguard.check.refuses_beyond", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == SB_EUSAGE &&
						     strstr(e.msg, "dt:") && strstr(e.msg, "stability limit"),
	      "rc %d: %s", e.code, e.msg);
	e = (sb_err){0};
	sc.dt = 0.1 * pi / 2000;
	CHECK("dtguard.check.warns_close", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == 0 && strstr(warn, "close to"),
	      "warn '%s'", warn);
	sc.dt = 0.07 * pi / 2000;
	CHECK("dtguard.check.silent_below_half", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == 0 && !warn[0],
	      "warn '%s'", warn);

	/* the shear spring (docs/model.md, "Tangential law"): its oscillation, 3 k_t / m_eff,
	 * is the faster one only for k_t > Y / 3; the default 2/7 Y and Y / 3 leave the limit
	 * 0.15 pi / 2000 alone, k_t = Y shortens it by sqrt(3), to 0.0866 pi / 2000 */
	sc.tangential = TANGENTIAL_SPRING;
	sc.dt = 0.14 * pi / 2000;
	e = (sb_err){0};
	CHECK("dtguard.spring.default_kt_as_viscous", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == 0, "%s", e.msg);
	sc.shear_stiffness = sc.stiffness / 3;
	CHECK("dtguard.spring.third_of_y_as_viscous", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == 0, "%s", e.msg);
	sc.shear_stiffness = sc.stiffness;
	sc.dt = 0.09 * pi / 2000;
	CHECK("dtguard.spring.stiff_refused", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == SB_EUSAGE, "rc %d", e.code);
	e = (sb_err){0};
	sc.dt = 0.085 * pi / 2000;
	CHECK("dtguard.spring.stiff_below_its_limit", dtguard_check(&sc, 0.5, warn, sizeof warn, &e) == 0, "%s", e.msg);
	return tl_done();
}
