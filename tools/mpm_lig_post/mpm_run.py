"""Running mpm_lig from a tool: one case into one output folder, its output in a log."""
import subprocess


def run_case(mpm_lig, case_path, out, log):
    """`mpm_lig CASE --output OUT`, stdout and stderr into `log`; a RuntimeError naming the
    case and the log when it fails (the tools end with exit 1 on it)."""
    with open(log, "w") as f:
        code = subprocess.call([mpm_lig, case_path, "--output", out], stdout=f,
                               stderr=subprocess.STDOUT)
    if code != 0:
        raise RuntimeError(f"{case_path}: mpm_lig exited {code} (see {log})")
