"""The closed forms as plain functions of lambda, against independent computations in NumPy and exact rationals."""
import math
from fractions import Fraction

import numpy as np
import pytest

import crankcheck
from conftest import EPS

LAMBDAS = [0.05, 0.3, 0.6, 0.9, 0.999]
N = 1 << 14  # FFT samples: the coefficients decay like q^n, q = (lam / (1 + sqrt(1 - lam^2)))^2 = 0.91 at 0.999,
             # so what the FFT folds back from harmonic N - n is below 1e-300 of the first


def fft_cosine_series(f):
    """A_0, A_1, ... of f(theta) = A_0 + sum A_n cos(n theta) from N samples."""
    theta = 2 * np.pi * np.arange(N) / N
    c = np.fft.rfft(f(theta)) / N
    out = 2 * c.real
    out[0] = c[0].real
    return out


def fft_sine_series(f):
    theta = 2 * np.pi * np.arange(N) / N
    return -2 * np.fft.rfft(f(theta)).imag / N


# The FFT's own rounding: each coefficient is a sum of N terms of size <= max |f| / N with a pairwise summation's error
# O(eps log2 N) (log2 N = 14): 32 eps x max |f| covers it. (max |f| <= 1 for the radical; <= 1 / sqrt(1 - lam^2) for
# its inverse, up to 22 at lam = 0.999; <= lam / (2 sqrt(1 - lam^2)) for eq 14's function.)
def fft_tolerance(max_f):
    return 32 * EPS * max_f


@pytest.mark.parametrize("lam", LAMBDAS)
def test_fourier_coefficients_against_an_fft(lam):
    order = 40
    root = lambda t: np.sqrt(1 - (lam * np.sin(t)) ** 2)
    a = crankcheck.radical_fourier_coefficients(lam, order)
    assert a.shape == (order + 1,)
    np.testing.assert_allclose(a, fft_cosine_series(root)[:order + 1], rtol=0, atol=fft_tolerance(1.0))
    assert not a[1::2].any()  # odd harmonics vanish exactly
    b = crankcheck.inverse_radical_fourier_coefficients(lam, order)
    inverse_max = 1 / math.sqrt(1 - lam * lam)
    np.testing.assert_allclose(b, fft_cosine_series(lambda t: 1 / root(t))[:order + 1], rtol=0,
                               atol=fft_tolerance(inverse_max))
    big_lambda = crankcheck.lambda_coefficients(lam, order)
    eq14 = lambda t: lam * np.sin(t) * np.cos(t) / root(t)
    np.testing.assert_allclose(big_lambda, fft_sine_series(eq14)[:order + 1], rtol=0,
                               atol=fft_tolerance(lam * inverse_max / 2))


def exact_series_coefficient(n, power):
    """The coefficient of lam^power in Lambda_n from another route than the library's: the generalised binomial
    series sqrt(1 - x) = sum_p C(1/2, p) (-x)^p with x = lam^2 sin^2, the cosine series of sin^(2p) (the coefficient
    of cos(2 m theta) is 2 (-1)^m C(2p, p - m) / 4^p), and Lambda_2m = 2m A_2m / lam."""
    m, p = n // 2, (power + 1) // 2
    if p < m:
        return Fraction(0)
    half_choose_p = Fraction(1)
    for i in range(p):
        half_choose_p *= (Fraction(1, 2) - i) / (i + 1)
    a_2m = half_choose_p * (-1) ** p * 2 * (-1) ** m * math.comb(2 * p, p - m) / Fraction(4) ** p
    return 2 * m * a_2m


@pytest.mark.parametrize("n", [2, 4, 6, 8, 10, 12])
def test_lambda_series_coefficients_are_exact_rationals(n):
    for power in range(1, 40, 2):
        got = crankcheck.lambda_series_coefficient(n, power)
        assert isinstance(got, Fraction)
        assert got == exact_series_coefficient(n, power), (n, power)
    # The misprint the errata name: the printed 0.022432 is 735/32768 = 0.0224304.
    assert crankcheck.lambda_series_coefficient(2, 9) == Fraction(735, 32768)


def test_the_printed_table_is_truncated_at_lambda_11():
    lam = 0.3
    printed = crankcheck.lambda_coefficients_as_printed(lam, 12)
    exact = crankcheck.lambda_coefficients(lam, 12)
    # Truncated after lam^11: the first term left out of Lambda_2 is of order lam^13 (times a coefficient < 1), and
    # each printed coefficient has six decimals (error < 5e-7 times lam^power).
    assert np.max(np.abs(printed - exact)) < lam ** 13 + 5e-7 * lam
    assert np.max(np.abs(printed - exact)) > 0


THETA = np.linspace(-7.0, 7.0, 1001)


@pytest.mark.parametrize("lam", [0.1, 0.3, 0.7])
def test_norton_two_term_is_13_3(lam):
    r, omega = 0.05, 300.0
    l = r / lam
    got = crankcheck.norton_two_term(THETA, lam, r=r, omega=omega)
    c1, s1, c2, s2 = np.cos(THETA), np.sin(THETA), np.cos(2 * THETA), np.sin(2 * THETA)
    expected = {
        "x_p": l - r * r / (4 * l) + r * (c1 + r / (4 * l) * c2),   # 13.3c
        "v_p": -r * omega * (s1 + r / (2 * l) * s2),                # 13.3d
        "a_p": -r * omega ** 2 * (c1 + r / l * c2),                 # 13.3e
        "j_p": r * omega ** 3 * (s1 + 2 * r / l * s2),              # d/dt of 13.3e
    }
    # Two computations of the same few terms, each within a few roundings of the terms' sizes: 8 eps x the sum of
    # the magnitudes (l + r for x, r omega^n (1 + 2 lam) for the derivatives).
    for key, scale in (("x_p", l + r), ("v_p", r * omega * 2), ("a_p", r * omega ** 2 * 3), ("j_p", r * omega ** 3 * 3)):
        np.testing.assert_allclose(got[key], expected[key], rtol=0, atol=8 * EPS * scale, err_msg=key)


@pytest.mark.parametrize("lam", [0.1, 0.3, 0.7, 0.95])
def test_exact_kinematics_and_their_series(lam):
    r, omega = 0.05, 300.0
    l = r / lam
    got = crankcheck.piston_kinematics(THETA, lam, r=r, omega=omega)
    s, c = np.sin(THETA), np.cos(THETA)
    root = np.sqrt(1 - (lam * s) ** 2)
    x = r * c + l * root                                                        # Norton 13.1d
    v = -r * omega * (s + lam * s * c / root)
    a = -r * omega ** 2 * (c + lam * (c * c - s * s) / root + lam ** 3 * s * s * c * c / root ** 3)
    # 16 eps x the scales of scales.h (l + r; r omega (1 + 1/root_min); r omega^2 (1 + 1/root_min^3)): two
    # arrangements of the same closed form.
    root_min = math.sqrt(1 - lam * lam)
    np.testing.assert_allclose(got["x_p"], x, rtol=0, atol=16 * EPS * (l + r))
    np.testing.assert_allclose(got["v_p"], v, rtol=0, atol=16 * EPS * r * omega * (1 + 1 / root_min))
    np.testing.assert_allclose(got["a_p"], a, rtol=0, atol=16 * EPS * r * omega ** 2 * (1 + root_min ** -3))
    # Norton's two-term form is off by O(lam^3) in a: clearly more than rounding, less than lam^3 r omega^2.
    norton = crankcheck.norton_two_term(THETA, lam, r=r, omega=omega)
    error = np.max(np.abs(norton["a_p"] - got["a_p"])) / (r * omega ** 2)
    assert 1e-3 * lam ** 3 < error < 2 * lam ** 3 / (1 - lam * lam) ** 1.5
    # The Fourier series with exact coefficients converges to the exact form: order 40 is below rounding up to 0.7,
    # and at 0.95 (q = 0.53) within q^21.
    series = crankcheck.fourier_piston_kinematics(THETA, lam, 40, r=r, omega=omega)
    q = (lam / (1 + root_min)) ** 2
    np.testing.assert_allclose(series["x_p"], got["x_p"], rtol=0, atol=(l + r) * (16 * EPS + 4 * q ** 21))


def test_scalar_angles_and_bad_arguments():
    one = crankcheck.piston_kinematics(0.5, 0.3)
    assert isinstance(one["x_p"], np.float64)
    with pytest.raises(ValueError, match="lam"):
        crankcheck.norton_two_term(THETA, 1.0)
    with pytest.raises(ValueError, match="lam"):
        crankcheck.piston_kinematics(THETA, 0.0)
    with pytest.raises(ValueError, match="finite"):
        crankcheck.piston_kinematics([0.0, np.nan], 0.3)
    with pytest.raises(ValueError):
        crankcheck.radical_fourier_coefficients(1.0, 4)
    # A round of attacks: order 1e7 ran for hours (the cost grows with the order's square); refused at once.
    for function in (crankcheck.radical_fourier_coefficients, crankcheck.inverse_radical_fourier_coefficients,
                     crankcheck.lambda_coefficients):
        with pytest.raises(ValueError, match="order: at most 10000"):
            function(0.3, 10**7)
    with pytest.raises(ValueError, match="order: at most 10000"):  # the same coefficients, per angle (a hostile round)
        crankcheck.fourier_piston_kinematics(THETA, 0.3, 10**6)
    assert len(crankcheck.radical_fourier_coefficients(0.3, 10000)) > 0
    with pytest.raises(ValueError):
        crankcheck.lambda_series_coefficient(3, 5)
    with pytest.raises(ValueError, match="order"):
        crankcheck.fourier_piston_kinematics(THETA, 0.3, 0)
