"""viscolube: friction of wet rubber contacts, from first principles.

The Python interface of libviscolube (the same library as the command line
`viscolube`; nothing is computed here). docs/PYTHON.md describes the API.

    import viscolube as vl
    db = vl.Database()                    # the default database, as the CLI
    r = db.friction(compound="sbr-unfilled", surface="paper-0.5um",
                    fluid="water", speed=0.01)
    r.mu, r.mu_Rc, r.u_min, r.regime, r.converged, r.warnings

Errors are `viscolube.Error` (subclasses per library status: InputError,
NotFoundError, ExistsError, DatabaseError, FileError, NoConvergenceError,
OutOfMemoryError, InternalError) with `.status` (the library's code) and
`.message` (its sentence). The library prints nothing.
"""

import math
import os
import sys
import warnings

try:
    import numpy as np
except ImportError as _e:  # say what is missing, for which interpreter
    raise ImportError(
        "viscolube needs NumPy, which is not installed for this interpreter "
        f"({sys.executable}): install it (Debian: python3-numpy), or use the "
        "interpreter the package was built for (cmake prints it: 'the Python "
        "package (target vl_python_core) is built for ...')") from _e
try:
    from . import _core
except ImportError as _e:
    # Python words a missing extension module as "cannot import name '_core'
    # from partially initialized module (most likely due to a circular
    # import)": it is simply not there
    _why = "" if "partially initialized" in str(_e) else f"; import error: {_e}"
    raise ImportError(
        "viscolube's extension viscolube._core is not built or not built for this "
        f"interpreter ({sys.executable}, Python {sys.version_info.major}."
        f"{sys.version_info.minor}): build the target vl_python_core (cmake --build "
        "build --target vl_python_core) and put build/python on PYTHONPATH"
        f"{_why}") from _e
from ._core import (DatabaseError, Error, ExistsError, FileError, InputError,
                    InternalError, NoConvergenceError, NotFoundError,
                    OutOfMemoryError)

__version__ = _core.PROJECT_VERSION
__all__ = ["FitWarning", "Database", "Curve", "Point", "Seal", "scene_text", "CURVE_COLUMNS",
           "Error",
           "InputError", "NotFoundError", "ExistsError", "DatabaseError",
           "FileError", "NoConvergenceError", "OutOfMemoryError",
           "InternalError"]

#: The columns of curve.csv, in order (the library's list).
CURVE_COLUMNS = tuple(_core.curve_columns())

# the library's "not given" for optional numbers
_ABSENT = math.nan


class FitWarning(UserWarning):
    """What an import of measured data warns of (the lines `compound add
    --measured` prints as 'warning: ...'): isotherms that do not join, a tan
    delta rise at the top of the window, Einf extrapolated, a rough fit."""


def _input_error(msg):
    """An InputError raised by the package itself (arguments that do not go
    together), shaped as the library's."""
    e = InputError(msg)
    e.status, e.message = 1, msg
    return e


def _num(v):
    return _ABSENT if v is None else float(v)


def _path(p):
    return None if p is None else os.fspath(p)


# The `accuracy` of a converged point that is not known to its error target.
UNRELIABLE = ("above_target", "no_estimate")


class Point(dict):
    """One operating point: the keys of `viscolube friction --json` (the
    columns of curve.csv) and how it was computed (eta_pa_s, a_T, a0_m,
    hrms_m, flow_factors, film_cutoff_m, temperature_c, points_solved);
    a ball's or an ellipsoid's also geometry, contact_area_m2,
    contact_length_m, contact_breadth_m, x_min_film_m, y_min_film_m,
    y_peak_m, cells_in_contact, cells_per_a0 (friction --json's).
    Keys are also attributes; `u_min` is `u_min_m`; `warnings` is a list.
    A point that did not converge has converged False and NaN physics;
    `reliable` is False for it and for a point above its error target or
    without an estimate (`accuracy` 'above_target' or 'no_estimate')."""

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    @property
    def u_min(self):
        return self["u_min_m"]

    @property
    def reliable(self):
        """Converged and known to its error target (what the program does
        not mark '!')."""
        return bool(self["converged"]) and self["accuracy"] not in UNRELIABLE


class Curve(dict):
    """A Stribeck curve: {column of curve.csv: numpy array}, one entry per
    sweep point. Float columns hold NaN where curve.csv has an empty cell
    (a point that did not converge, a quantity not defined for the scene);
    `converged` (bool) says which points are solved, `iterations` is int,
    `regime`, `accuracy` and `warnings` are arrays of str ('' for a failed
    point); the property `reliable` (bool array) is True where a point
    converged and is known to its error target: the points the program marks
    '!' are False.
    A seal scene ([seal] stroke) adds the seal columns of curve.csv
    (docs/FORMATS.md): `stroke` (str), flux_m2_s, friction_n_per_m, the
    instroke's *_in columns, volume_out_m3, volume_back_m3, and
    converged_in, tight as 1.0/0.0 (NaN when not known).
    A point contact ([contact] geometry = ball or ellipsoid) adds its
    columns (docs/POINT_CONTACT.md): `geometry` (str), contact_area_m2,
    contact_length_m, contact_breadth_m, x_min_film_m, y_min_film_m,
    y_peak_m, cells_in_contact, cells_per_a0.

    .info    the curve's context: compound, surface, fluid, quantity,
             eta_pa_s, tau_s, a0_m, p0_pa, hrms_m, flow_factors,
             film_cutoff_m, temperature_c, a_T
    .fields  one dict per point the scene asked fields at (fields_at):
             index, v0_m_s and the arrays of fields/NNN.csv (x_m,
             x_over_a0, p_f_pa, p_c_pa, u_m, area_ratio, film_fraction,
             cell_width_m; a point contact: x_m, y_m, x_over_a0,
             y_over_a0, p_c_pa, u_m on the cells of the half y >= 0)
    """

    def __init__(self, raw):
        super().__init__()
        for name, values in raw["curve"].items():
            if isinstance(values, list):
                values = np.array(values, dtype=str)
            self[name] = values
        self.info = raw["info"]
        self.fields = raw["fields"]

    @property
    def reliable(self):
        """Boolean array: converged and known to the error target (False
        where the program marks '!', and where a point failed)."""
        return self["converged"] & ~np.isin(self["accuracy"], UNRELIABLE)

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    def structured(self):
        """The curve as one numpy structured array (a record per point)."""
        cols = list(self.keys())
        return np.rec.fromarrays([self[c] for c in cols], names=cols)


class Seal(dict):
    """A seal's two strokes at each speed (`viscolube seal`, seal.csv):
    {column: numpy array}, the columns of seal.csv in its order
    (`v0_m_s`, `friction_out_n_per_m`, `friction_in_n_per_m`, `mu_out`,
    `mu_in`, `u_min_out_m`, ..., `flux_out_m2_s`, `flux_in_m2_s`, the error
    estimates `error_*` of the friction and `flux_error_*` of the flux,
    `volume_out_m3`, `volume_back_m3`, `tight`, `converged_*` as float64
    1.0/0.0, and `accuracy_*`, `warnings_*` as arrays of str). NaN where
    seal.csv has an empty cell (a stroke that did not converge; the volumes
    and `tight` without [seal] rod_diameter_m and stroke_length_m).

    .curve   the run's Curve (the outstroke's rows with the seal columns)
    .info    as Curve.info
    """

    def __init__(self, raw):
        super().__init__()
        for name, values in raw["seal"].items():
            if isinstance(values, list):
                values = np.array(values, dtype=str)
            self[name] = values
        self.curve = Curve(raw)
        self.info = self.curve.info

    @property
    def tight(self):
        """Boolean array: the seal carries back at least what it lets out
        (False where not known)."""
        return self["tight"] == 1.0

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None


def _ini_value(v):
    if isinstance(v, bool):
        return "on" if v else "off"
    if isinstance(v, (list, tuple)):
        return ", ".join(_ini_value(x) for x in v)
    if isinstance(v, float):
        return repr(v)
    text = str(v)
    if "\n" in text or "\r" in text:
        raise _input_error("scene value %r: one line only" % text)
    return text


def scene_text(scene):
    """The INI text of a scene given as {section: {key: value}} (docs/
    FORMATS.md): booleans become on/off, lists comma-separated, floats
    their shortest exact form."""
    lines = []
    for section, keys in scene.items():
        lines.append("[%s]" % section)
        for key, value in keys.items():
            lines.append("%s = %s" % (key, _ini_value(value)))
        lines.append("")
    return "\n".join(lines)


class Database:
    """The material database (SQLite). path None: the default one, as the
    command line chooses it ($VISCOLUBE_DB, else $XDG_DATA_HOME/viscolube/
    materials.db, else ~/.local/share/viscolube/materials.db), created on
    first use with the materials shipped in the library. Use from one
    thread at a time; `with Database(...) as db:` closes it."""

    def __init__(self, path=None):
        self._db = _core.Database(_path(path))

    def close(self):
        self._db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def path(self):
        return self._db.path()

    @property
    def readonly(self):
        return self._db.readonly()

    # ---- materials ---------------------------------------------------------

    def compounds(self):
        """Every compound as a dict (name, class, e_inf_pa, e0_pa, nu,
        tau_s and A arrays, tref_c, wlf_c1, wlf_c2_k, method, ...)."""
        return self._db.compounds()

    def surfaces(self):
        """Every surface as a dict (name, kind, hrms_m, rms_slope, q0_per_m,
        q1_per_m, hurst, c0_m4, n_points, ...)."""
        return self._db.surfaces()

    def fluids(self):
        """Every fluid as a dict (name, viscosity_pa_s, tref_c,
        viscosity_law, vogel_b_k, vogel_c_k, law_tmin_c, law_tmax_c, ...)."""
        return self._db.fluids()

    def add_compound(self, name, prony=None, measured=None, tau_s=None, A=None,
                     e_inf_pa=None, nu=None, class_name="other", description="",
                     tref_c=None, wlf_c1=None, wlf_c2_k=None, freq_unit=None,
                     modulus_unit=None, temp_unit=None, terms_per_decade=None,
                     fit_weights=None):
        """Adds a compound from one of: prony=CSV file of tau_s,A (with
        e_inf_pa, nu), tau_s=/A= sequences (with e_inf_pa, nu), or
        measured=DMA file (fitted; freq_unit, modulus_unit, temp_unit,
        tref_c, nu, terms_per_decade, fit_weights as `compound add
        --measured`). tref_c defaults to 20 C for a Prony series. Nothing
        is stored when anything is refused. The import's warnings (as the
        CLI prints them) are raised as FitWarning (warnings.warn); its
        notes, one sentence a line, are returned (None for a Prony series)."""
        notes = self._db.add_compound(
            name, prony=_path(prony), tau_s=tau_s, A=A, e_inf_pa=_num(e_inf_pa),
            nu=_num(nu), measured=_path(measured), class_name=class_name,
            description=description, tref_c=_num(tref_c), wlf_c1=_num(wlf_c1),
            wlf_c2_k=_num(wlf_c2_k), freq_unit=freq_unit,
            modulus_unit=modulus_unit, temp_unit=temp_unit,
            terms_per_decade=0.0 if terms_per_decade is None else float(terms_per_decade),
            fit_weights=fit_weights)
        for line in (notes or "").splitlines():
            if line.startswith("warning: "):
                warnings.warn(f"{name}: {line[9:]}", FitWarning, stacklevel=2)
        return notes

    def add_surface(self, name, psd=None, hurst=None, q0_per_m=None,
                    q1_per_m=None, hrms_m=None, description=None, topography=None):
        """Adds a surface: psd=CSV file (q, C), topography=a measured height
        map or profile (its power spectrum, as `surface add --topography`),
        or self-affine with hurst, q0_per_m, q1_per_m and hrms_m."""
        self._db.add_surface(name, psd=_path(psd), hurst=_num(hurst),
                             q0_per_m=_num(q0_per_m), q1_per_m=_num(q1_per_m),
                             hrms_m=_num(hrms_m), description=description,
                             topography=_path(topography))

    def add_fluid(self, name, viscosity_pa_s, tref_c=20.0, vogel_b_k=None,
                  vogel_c_k=None, law_range_c=None, description=""):
        """Adds a Newtonian fluid; with vogel_b_k, vogel_c_k and law_range_c
        = (tmin, tmax) also its Vogel viscosity law."""
        lo, hi = (None, None) if law_range_c is None else law_range_c
        self._db.add_fluid(name, float(viscosity_pa_s), tref_c=float(tref_c),
                           vogel_b_k=_num(vogel_b_k), vogel_c_k=_num(vogel_c_k),
                           law_tmin_c=_num(lo), law_tmax_c=_num(hi),
                           description=description)

    def remove_compound(self, name):
        self._db.remove("compound", name)

    def remove_surface(self, name):
        self._db.remove("surface", name)

    def remove_fluid(self, name):
        self._db.remove("fluid", name)

    # ---- solving -----------------------------------------------------------

    @staticmethod
    def _given(**kw):
        """The keywords given (not None): the library has the defaults."""
        return {k: v for k, v in kw.items() if v is not None}

    @classmethod
    def _conditions(cls, load, radius, sigma_s, temperature, flow_factors,
                    film_cutoff, grid, target_error=None):
        return cls._given(load_n_per_m=load, radius_m=radius, sigma_s_pa=sigma_s,
                          temperature_c=temperature, flow_factors=flow_factors,
                          film_cutoff_m=film_cutoff, grid=grid, target_error=target_error)

    @classmethod
    def _body(cls, geometry, surface, fluid, load, load_n, radius, radii, grid,
              flow_factors, film_cutoff):
        """The rigid body's keywords for the library: those of a cylinder
        (load, radius) or of a point contact (geometry, load_n, radius or
        radii), refused as the command line refuses its options (a missing
        one TypeError, a misplaced one InputError, naming the keyword)."""
        if geometry is None:
            geometry = "cylinder"
        if not isinstance(geometry, str):
            raise TypeError("geometry: expected 'cylinder', 'ball' or 'ellipsoid' (got %s)"
                            % type(geometry).__name__)
        if geometry not in ("cylinder", "ball", "ellipsoid"):
            raise _input_error("geometry: expected cylinder, ball or ellipsoid (got '%s')"
                               % geometry)
        point = geometry != "cylinder"
        if not point and (surface is None or fluid is None):
            raise TypeError("missing %s: a cylinder needs a surface and a fluid (a ball or an "
                            "ellipsoid may go without: geometry=)"
                            % ("surface" if surface is None else "fluid"))
        if not point and load_n is not None:
            raise _input_error("load_n (a total load, N) is a ball's or an ellipsoid's "
                               "(geometry=): a cylinder takes load (N/m)")
        if geometry != "ellipsoid" and radii is not None:
            raise _input_error("radii is an ellipsoid's: a %s takes radius (m)" % geometry)
        if not point:
            return cls._given(load_n_per_m=load, radius_m=radius)
        if load is not None:
            raise _input_error("load (N per metre of a cylinder's length) is not a %s's: it "
                               "takes load_n (N), its total load" % geometry)
        if load_n is None:
            raise TypeError("missing load_n (the %s's total load, N)" % geometry)
        if geometry == "ball" and radius is None:
            raise TypeError("missing radius (the ball's radius, m)")
        if geometry == "ellipsoid" and radius is not None:
            raise _input_error("radius is not an ellipsoid's: it takes radii=(rx, ry) (m, "
                               "along the sliding direction and across it)")
        if geometry == "ellipsoid":
            if radii is None or isinstance(radii, str) or len(radii) != 2:
                raise TypeError("radii: an ellipsoid needs two radii (rx, ry), m: along the "
                                "sliding direction and across it")
            radius, radius_y = (float(r) for r in radii)
        else:
            radius_y = None
        if grid is not None:
            raise _input_error("grid sets a line contact's cells: a %s's are planned per "
                               "point (docs/POINT_CONTACT.md)" % geometry)
        if surface is None and (flow_factors is not None or film_cutoff is not None):
            raise _input_error("%s applies to a rough contact (surface) only"
                               % ("flow_factors" if flow_factors is not None else "film_cutoff"))
        return cls._given(geometry=geometry, load_n=float(load_n), radius_m=float(radius),
                          radius_y_m=radius_y)

    def friction(self, compound, surface=None, fluid=None, speed=None, load=None,
                 radius=None, sigma_s=None, temperature=None, flow_factors=None,
                 film_cutoff=None, grid=None, geometry=None, load_n=None, radii=None,
                 target_error=None):
        """One operating point, exactly as `viscolube friction`, with its
        defaults (None): speed in m/s, load in N/m (117), radius in m
        (1e-3), sigma_s in Pa (1e6), temperature in C (every material at its
        reference temperature), flow_factors 'persson-emt' (default),
        'patir-cheng' or 'smooth', film_cutoff in m (persson-emt: 1e-9),
        grid the uniform cells (2928), target_error the relative error of
        mu the point should meet (0.01). geometry 'ball' (radius, load_n: the
        total load in N) or 'ellipsoid' (radii=(rx, ry) in m along and
        across the sliding direction, load_n): the point contact of `run`,
        surface and fluid optional (smooth, dry), no load or grid; its
        Point has the point contact's keys too (`friction --json`'s).
        Returns a Point; a point that does not converge is returned with
        converged False."""
        if speed is None:
            raise TypeError("friction(): missing speed (m/s)")
        body = self._body(geometry, surface, fluid, load, load_n, radius, radii, grid,
                          flow_factors, film_cutoff)
        raw = self._db.friction(
            compound, surface, fluid, speed_m_s=speed, **body,
            **self._conditions(None, None, sigma_s, temperature, flow_factors, film_cutoff,
                               grid, target_error))
        raw["warnings"] = [w for w in raw["warnings"].split(";") if w]
        return Point(raw)

    def calibrate(self, compound, surface, fluid, measured=None, v=None, mu=None,
                  law="constant", load=None, radius=None, temperature=None, save=False,
                  description=None):
        """Calibrates the sigma_s law of the pair (compound, surface, fluid)
        on a measured Stribeck curve, as `viscolube pair calibrate`: a file
        (measured: speed with its unit in the header, and mu) or the
        sequences v (m/s) and mu; law 'constant', 'eyring' or 'dewetting';
        the measurement's load (N/m, 117), radius (m, 1e-3), temperature
        (C). Returns a dict: law, parameters, ci95 (95 % half-widths),
        rms_log10_mu, fits (and why not), n_points, n_used,
        unreached_v_m_s, uninformative_v_m_s, sweep_seconds, fit_seconds,
        saved. save=True stores it as the pair (InputError when the law
        does not fit; ExistsError when the pair exists)."""
        kw = self._given(load_n_per_m=load, radius_m=radius, temperature_c=temperature,
                         description=description)
        return self._db.calibrate(
            compound, surface, fluid, measured=_path(measured),
            v_m_s=None if v is None else [float(x) for x in v],
            mu=None if mu is None else [float(x) for x in mu], law=law, save=bool(save), **kw)

    def run(self, scene):
        """Runs a scene: a path to an INI file (cases/*.ini) or a dict
        {section: {key: value}} (see scene_text). Returns a Curve, or for a
        scene with several fluids {fluid: Curve} in the scene's order."""
        if isinstance(scene, dict):
            raw = self._db.run_scene(scene_text(scene), "<scene dict>")
        else:
            raw = self._db.run_scene(None, _path(scene))
        curves = [Curve(r) for r in raw]
        if len(curves) == 1:
            return curves[0]
        return {c.info["fluid"]: c for c in curves}

    def seal(self, scene):
        """Both strokes of a seal scene, exactly as `viscolube seal`: a
        path or a dict as run() takes; the scene must have [contact] moving
        = counterface and a fluid ([seal] stroke is set to both). Returns a
        Seal, or for several fluids {fluid: Seal}."""
        if isinstance(scene, dict):
            raw = self._db.run_scene(scene_text(scene), "<scene dict>", seal=True)
        else:
            raw = self._db.run_scene(None, _path(scene), seal=True)
        seals = [Seal(r) for r in raw]
        if len(seals) == 1:
            return seals[0]
        return {s.info["fluid"]: s for s in seals}

    def compare(self, compounds, surface=None, fluid=None, v_from=None, v_to=None,
                points=None, load=None, radius=None, sigma_s=None,
                temperature=None, flow_factors=None, film_cutoff=None,
                grid=None, geometry=None, load_n=None, radii=None,
                from_speed=None, to_speed=None, target_error=None):
        """Stribeck curves of several compounds, exactly as `viscolube
        compare`: v0*eta from v_from (1e-12) to v_to (0.1 Pa m), or the
        speed from from_speed to to_speed (m/s), points (45) log-spaced;
        the other conditions as friction (a ball's or an ellipsoid's too:
        their range must be given, in m/s when dry).
        Every compound is checked before anything is computed. Returns
        {compound: Curve}, each the curve.csv `compare` writes."""
        if isinstance(compounds, str):
            compounds = [compounds]
        body = self._body(geometry, surface, fluid, load, load_n, radius, radii, grid,
                          flow_factors, film_cutoff)
        cond = dict(body, **self._conditions(None, None, sigma_s, temperature,
                                             flow_factors, film_cutoff, grid, target_error))
        sweep = self._sweep(geometry, fluid, v_from, v_to, from_speed, to_speed)
        sweep.update(self._given(points=points))
        for c in compounds:
            self._db.check_query(c, surface, fluid, **cond, **sweep)
        return {c: Curve(self._db.run_query(c, surface, fluid, **cond, **sweep))
                for c in compounds}

    @classmethod
    def _sweep(cls, geometry, fluid, v_from, v_to, from_speed, to_speed):
        """compare's range for the library, refused as the command line
        refuses --from/--to and --from-speed/--to-speed."""
        speeds = from_speed is not None or to_speed is not None
        if speeds and (from_speed is None or to_speed is None):
            raise TypeError("from_speed and to_speed go together")
        given = v_from is not None or v_to is not None
        if speeds and given:
            raise _input_error("give the range in m/s (from_speed, to_speed) or in v0 eta "
                               "(v_from, v_to), not both")
        if fluid is None and given:
            raise _input_error("v_from/v_to: a dry contact (no fluid) has no v0 eta: give the "
                               "range in m/s (from_speed, to_speed)")
        if geometry not in (None, "cylinder") and not speeds and not given:
            raise TypeError("geometry=%r needs its range: from_speed and to_speed (m/s), or "
                            "v_from and v_to (v0 eta, Pa m); the default 1e-12 .. 0.1 Pa m is a "
                            "line contact's (a point contact's point costs seconds)" % geometry)
        if not speeds:
            return cls._given(v_from=v_from, v_to=v_to)
        if not 0 < from_speed < to_speed:
            raise _input_error("from_speed, to_speed: need 0 < from_speed < to_speed")
        return dict(v_from=float(from_speed), v_to=float(to_speed), in_speed=True)
