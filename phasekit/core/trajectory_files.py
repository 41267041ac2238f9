"""A trajectory's files: its run table as CSV, Parquet or NetCDF with the units and long names of
every column (:func:`write_run_table`), and the whole trajectory as NetCDF or Parquet."""

from __future__ import annotations

from .trajectory_io import run_table


def write_run_table(traj, path, times=None, *, n: int = 2001, suffixes=(".csv", ".parquet", ".nc"), scale=None):
    """Write :func:`run_table` to ``path`` (:func:`phasekit.write_table`).

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    path : str or os.PathLike
        The file, ending in one of ``suffixes`` (written atomically).
    times, n, scale
        As for :func:`run_table` (``scale``: the columns in real units, each named in its
        ``units``).
    suffixes : tuple of str, optional
        The file types allowed.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        For a path not ending in one of ``suffixes``, an invalid ``n`` or a time outside the run.
    PhasekitError
        If the packages of the file type (``phasekit[data]``) are missing.
    """
    from ..io.tables import check_path, write_table

    path = check_path(path, suffixes)
    return write_table(run_table(traj, times, n=n, scale=scale), path)


def write_netcdf(traj, path, times=None, *, n: int = 2001, scale=None):
    """Write :func:`run_table` to a NetCDF file (``phasekit[data]``): the Dataset of
    :func:`trajectory_xarray`.

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    path : str or os.PathLike
        The file, ending in .nc (written atomically).
    times, n, scale
        As for :func:`trajectory_xarray` (``scale``: real units, :func:`run_table`).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        For a path not ending in .nc, an invalid ``n`` or a time outside the run.
    PhasekitError
        If the packages of ``phasekit[data]`` are missing.
    """
    return write_run_table(traj, path, times, n=n, suffixes=(".nc",), scale=scale)


def write_parquet(traj, path, times=None, *, n: int = 2001, scale=None):
    """Write :func:`run_table` to a Parquet file, units and inputs in its metadata
    (``phasekit[data]``).

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    path : str or os.PathLike
        The file, ending in .parquet (written atomically).
    times, n, scale
        As for :func:`trajectory_xarray` (``scale``: real units, :func:`run_table`).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ParameterError
        For a path not ending in .parquet, an invalid ``n`` or a time outside the run.
    PhasekitError
        If pyarrow (``phasekit[data]``) is missing.
    """
    return write_run_table(traj, path, times, n=n, suffixes=(".parquet",), scale=scale)
