function znn_circle(out)
% ZNN_CIRCLE  A trajectory made outside driftbench, to be scored by it.
%
%   znn_circle(out) integrates kong2019's ZNN repetitive scheme (22) on the Katana 6M180
%   tracing kong2019's circle, solved by a linear zeroing network, and writes the trajectory to
%   the CSV file out (default 'znn_circle.csv') in the columns `reproduce score` reads:
%   t, theta_1..theta_5 (rad), thetadot_1..thetadot_5 (rad/s, the network's command x); an
%   out ending in '.mat' is a MAT-file (v7) with the variables t (m x 1) and
%   y = [theta, thetadot] (m x 10, a row per instant) instead.
%   Everything is written here from the papers' equations (docs/robots.md, docs/paths.md,
%   docs/experiments.md); nothing is read from driftbench. It is the task
%   "kong2019-circle / znn-eq22" of experiments/kong2019.toml:
%
%     scheme, kong2019 (22):  min x'x/2 + mu (theta - theta*0)'x   s.t.  J(theta) x = b,
%                             b = rdot*(t) + k_p (r*(t) - f(theta)),  thetadot = x;
%     network (linear ZNN):   y = [x; lambda], Q = [I J'; J 0], u = [-mu (theta - theta*0); b],
%                             Q ydot = -Qdot y + udot - gamma (Q y - u),  y(0) = 0;
%     arm, kong2019 (2):      h = l2 C2 + l3 C23 + L S234,
%                             f = [C1 h; S1 h; l1 - L C234 + l2 S2 + l3 S23];
%     path (circle):          r* = f(theta*0) + rad [cos(phi) - 1; sin(phi); 0],
%                             phi = 2 pi sin^2(pi t / (2 T)).
%
%   Run from the repository root (Octave or MATLAB):
%     octave --no-gui --quiet --eval "addpath('examples/octave'); znn_circle('znn.csv')"
%     cargo run --release -p reproduce -- score znn.csv --task "kong2019-circle / znn-eq22"
%   (the same with znn.mat for a MAT-file).
if nargin < 1
  out = 'znn_circle.csv';
end
T = 9;                          % duration (s)
rad = 0.05;                     % circle radius (m)
mu = 1; k_p = 1; gamma = 1;     % scheme gain, position feedback, network gain
theta_star0 = [2*pi/5; pi/2; 0; -pi/6; pi/3];
theta0 = theta_star0 + [0; 0; 0; 0; 0.5];
r_start = katana_position(theta_star0);
n = 5; m = 3;

rhs = @(t, y) znn_rhs(t, y, n, m, T, rad, r_start, theta_star0, mu, k_p, gamma);
opts = odeset('RelTol', 1e-10, 'AbsTol', 1e-12);
t_out = linspace(0, T, 451)';
[t, y] = ode45(rhs, t_out, [theta0; zeros(n + m, 1)], opts);

t_and_y = [t, y(:, 1:2 * n)];
if numel(out) > 4 && strcmpi(out(end - 3:end), '.mat')
  y = t_and_y(:, 2:end);
  save(out, 't', 'y', '-v7');
  return
end
fid = fopen(out, 'w');
fprintf(fid, 't');
fprintf(fid, ',theta_%d', 1:n);
fprintf(fid, ',thetadot_%d', 1:n);
fprintf(fid, '\n');
fprintf(fid, [repmat('%.17g,', 1, 2 * n) '%.17g\n'], t_and_y');
fclose(fid);
end

function dy = znn_rhs(t, y, n, m, T, rad, r_start, theta_star0, mu, k_p, gamma)
% The coupled system: thetadot = x, and the zeroing network's ydot.
theta = y(1:n);
z = y(n + 1:end);
x = z(1:n);
[r, rdot, rddot] = circle(t, T, rad, r_start);
J = katana_jacobian(theta);
Jdot = jacobian_dot(theta, x);
Q = [eye(n), J'; J, zeros(m)];
u = [-mu * (theta - theta_star0); rdot + k_p * (r - katana_position(theta))];
Qdot = [zeros(n), Jdot'; Jdot, zeros(m)];
udot = [-mu * x; rddot + k_p * (rdot - J * x)];
dy = [x; Q \ (-Qdot * z + udot - gamma * (Q * z - u))];
end

function [r, rdot, rddot] = circle(t, T, rad, r_start)
% kong2019's circle under the rest-to-rest time law (docs/paths.md).
phi = 2 * pi * sin(pi * t / (2 * T))^2;
phidot = (pi^2 / T) * sin(pi * t / T);
phiddot = (pi^3 / T^2) * cos(pi * t / T);
d1 = rad * [-sin(phi); cos(phi); 0];
d2 = rad * [-cos(phi); -sin(phi); 0];
r = r_start + rad * [cos(phi) - 1; sin(phi); 0];
rdot = d1 * phidot;
rddot = d2 * phidot^2 + d1 * phiddot;
end

function [l1, l2, l3, L] = katana_lengths()
% Katana 6M180 link lengths (m), L = l4 + l5 (docs/robots.md).
l1 = 0.2015; l2 = 0.19; l3 = 0.139; L = 0.1523 + 0.1505;
end

function f = katana_position(th)
% kong2019 (2): the tool position.
[l1, l2, l3, L] = katana_lengths();
h = l2 * cos(th(2)) + l3 * cos(th(2) + th(3)) + L * sin(th(2) + th(3) + th(4));
f = [cos(th(1)) * h; sin(th(1)) * h;
     l1 - L * cos(th(2) + th(3) + th(4)) + l2 * sin(th(2)) + l3 * sin(th(2) + th(3))];
end

function J = katana_jacobian(th)
% df/dtheta of kong2019 (2), by hand (joint 5, the wrist roll, does not move the tool).
[l1, l2, l3, L] = katana_lengths();
C2 = cos(th(2)); S2 = sin(th(2));
C23 = cos(th(2) + th(3)); S23 = sin(th(2) + th(3));
C234 = cos(th(2) + th(3) + th(4)); S234 = sin(th(2) + th(3) + th(4));
h = l2 * C2 + l3 * C23 + L * S234;
dh = [-l2 * S2 - l3 * S23 + L * C234, -l3 * S23 + L * C234, L * C234];
C1 = cos(th(1)); S1 = sin(th(1));
J = [-S1 * h, C1 * dh, 0;
      C1 * h, S1 * dh, 0;
      0, h, l3 * C23 + L * S234, L * S234, 0];
end

function Jdot = jacobian_dot(th, thd)
% dJ/dt = sum_i dJ/dtheta_i thetadot_i, by the complex step (exact to rounding).
h = 1e-30;
Jdot = imag(katana_jacobian(th + 1i * h * thd)) / h;
end
