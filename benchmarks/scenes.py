"""Scene generators shared by tests and benchmarks."""
import pathlib


def chain_deck(n, penalty=1e4, penalty1=20.0, end_time=1.0, tol=1e-6):
    """A chain of `n` point masses linked by bilateral distance penalties, the first one
    pinned to ground, released horizontally under gravity (6 n states, sparse coupling)."""
    els = ['<Body_Rigid id="1" isground="TRUE"/>', '<Reference_Marker id="1" body_id="1"/>',
           '<Force_Gravity grav_z="-9.81"/>']
    for i in range(n):
        bid, mid = 100 + i, 1000 + i
        els.append(f'<Reference_Marker id="{mid}" body_id="{bid}" pos_x="{0.1 * (i + 1)}"/>')
        els.append(f'<Body_Point id="{bid}" cg_id="{mid}" mass="0.1"/>')
        prev = 1 if i == 0 else mid - 1
        els.append(f'<Force_Penalty id="{i + 1}" expr="DM({mid},{prev}) - 0.1" '
                   f'penalty="{penalty}" penalty1="{penalty1}"/>')
    last = 1000 + n - 1
    els.append(f'<Post_Request id="1" expr1="DX({last})" expr2="DZ({last})" '
               f'expr3="PFORCE(1)" name1="x_end" name2="z_end" name3="tension_1"/>')
    els.append(f'<Param_Transient integr_tol="{tol}"/>')
    return ("<MotionSolve><Model>\n" + "\n".join(els) + "\n</Model>\n"
            f'<Simulate analysis_type="Transient" end_time="{end_time}" print_interval="0.01"/>\n'
            "</MotionSolve>\n")


#: The stiff penalty pendulum of issue 5 (decks/stiff_penalty_pendulum.xml): 1 kg on a bilateral
#: penalty rod (k = 1e8, c = 2e4, critical), released horizontally, 10 s, outputs every 0.01 s.
PENDULUM = (pathlib.Path(__file__).resolve().parent.parent / "decks"
            / "stiff_penalty_pendulum.xml").read_text()
