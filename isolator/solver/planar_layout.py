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
