"""The one error type of the post-processing readers: bad or missing input."""


class InputError(Exception):
    """An output directory, file, column or dataset is missing or malformed."""
