"""What the example scripts read from a run's output folder (imported by examples/*/analyze.py)."""
import csv


def read_sensors(path):
    """The columns of a sensors.csv (comment lines skipped) as {name: [float, ...]}."""
    with open(path) as handle:
        rows = [line for line in handle if not line.startswith("#")]
    reader = csv.reader(rows)
    header = next(reader)
    columns = {name: [] for name in header}
    for row in reader:
        for name, value in zip(header, row):
            columns[name].append(float(value))
    return columns
