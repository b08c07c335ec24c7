"""The data layout shared by the planar kernel and its Python driver.

The compiled loop (:mod:`planar_kernel`) returns plain arrays; these constants say what
each slot holds: the event kinds, the status bits, the summary vector and the speed and
tolerance scales the driver (:mod:`planar`) builds.  The loop guards are here too, since
the driver's messages quote them.
"""

from __future__ import annotations

# event kinds: the 1-D vocabulary (breakaway, stick, reversal) + uplift, landing
EV_BREAKAWAY = 0
EV_STICK = 1
EV_REVERSAL = 2
EV_UPLIFT = 3
EV_LANDING = 4

MAX_EVENTS_PER_INTERVAL = 1000  #: chatter guard
MAX_STEPS_PER_INTERVAL = 100000  #: hang guard

STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2
STATUS_STEP_LIMIT = 4

# summary layout
S_PEAK_X = 0
S_PEAK_V = 1
S_PEAK_A = 2
S_SLIP_TIME = 3
S_UPLIFT_TIME = 4
S_N_UPLIFTS = 5
S_E_IN = 6
S_E_F = 7
S_E_V = 8
S_N_EVENTS = 9
S_STATUS = 10
S_N_STEPS = 11
S_N_REJECTED = 12  #: rejected steps (error or domain)
S_STEPS_START = 13  #: steps in the START form (after a break-away)
S_STEPS_LOG = 14  #: steps in the LOG form (approach to a stop)
S_STEPS_LIMITED = 15  #: Cartesian steps shortened to the stability bound (slow sliding)
S_SUB_LAND = 16  #: DOP853 sub-steps spent landing on an instant (sample, r_switch, re-stop)
S_SUB_PEAK = 17  #: DOP853 sub-steps spent locating peaks inside steps
S_SIZE = 18

# scales layout (built by isolator.solver.planar)
SC_R_MIN = 0  #: speed at which the LOG form hands over to the closed-form finish [m/s]
SC_R_SWITCH = 1  #: speed at which START hands over to Cartesian form [m/s]
SC_X_FLOOR = 2  #: displacement floor of the absolute tolerance [m]
SC_V_FLOOR = 3  #: speed floor of the absolute tolerance [m/s]
SC_R_SWITCH_LO = 4  #: lowest START → Cartesian hand-over speed (where the slaved direction lags much) [m/s]
SC_SIZE = 5

# the rim of a pendulum with a displacement capacity (isolator.solver.planar_rim): events it adds
EV_RIM_IMPACT = 5  #: a plastic impact on the rim (|X| = d moving outward)
EV_RIM_LEAVE = 6  #: the slider leaves the rim (the rim's reaction falls to zero)

#: the ``rim`` vector of the kernel: in, the rim radius (inf: none) and where and how a run restarts;
#: out, where it stopped at the rim
RM_RADIUS = 0  #: d [m]; inf for no rim
RM_START = 1  #: RS_FRESH, RS_START (from rest, the START form) or RS_SLIDE (Cartesian, velocity given)
RM_I = 2  #: sample interval of the restart (in) or of the rim contact (out)
RM_TAU = 3  #: local time in that interval [s]
RM_X1 = 4
RM_X2 = 5  #: X [m]
RM_V1 = 6
RM_V2 = 7  #: V [m/s]
RM_HIT = 8  #: out: 1 when the run stopped at the rim
RM_SIZE = 9
RS_FRESH = 0
RS_START = 1
RS_SLIDE = 2
#: a step is checked for the rim when |X| or the running peak exceeds d (1 + RIM_SLACK): a motion that only
#: grazes the circle from inside after leaving it (rounding) is not an impact
RIM_SLACK = 1e-12
