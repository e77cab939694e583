"""The SHADE denoiser of shade-sim (src/gen/model.rs) written again in PyTorch, for speed comparison.

Same layers, widths and operations: object tokens + contact-box tokens through DiT blocks with
adaLN-Zero, a time MLP on 64 sinusoidal features, PointNets for floor-plan and free-space points, and
DDPM sampling with T = 200. Weights are random (speed does not depend on them).

Prints one JSON line: the fastest of several runs (on a shared machine other work only ever slows a
run down), in seconds, of 200-step sampling of a batch (as written, every step runs
the whole forward; and with the conditions encoded once per batch, as shade-sim's sampler does) and
of one training step (forward, backward, AdamW) of a batch.
Usage: python dit_reference.py [--sample-batch 16] [--train-batch 32] [--repeats 5] [--threads 2]
"""
import argparse
import json
import math
import time

import torch
import torch.nn as nn
import torch.nn.functional as F


class PointNet(nn.Module):
    def __init__(self, inp, width, out):
        super().__init__()
        self.l0, self.l1, self.l2 = nn.Linear(inp, width), nn.Linear(width, 2 * width), nn.Linear(2 * width, out)

    def forward(self, p):
        return self.l2(F.relu(self.l1(F.relu(self.l0(p))))).amax(dim=1)


def layer_norm(x):
    mean = x.mean(-1, keepdim=True)
    c = x - mean
    return c / torch.sqrt((c * c).mean(-1, keepdim=True) + 1e-6)


def modulate(x, shift, scale):
    return x * (1 + scale) + shift


class Block(nn.Module):
    def __init__(self, d, heads, ratio):
        super().__init__()
        self.modulation = nn.Linear(d, 6 * d)
        nn.init.zeros_(self.modulation.weight)
        nn.init.zeros_(self.modulation.bias)
        self.qkv, self.proj = nn.Linear(d, 3 * d), nn.Linear(d, d)
        self.fc1, self.fc2 = nn.Linear(d, ratio * d), nn.Linear(ratio * d, d)
        self.heads = heads

    def attention(self, h, bias):
        b, n, d = h.shape
        dh = d // self.heads
        qkv = self.qkv(h).reshape(b, n, 3, self.heads, dh)
        q, k, v = (qkv[:, :, i].transpose(1, 2) for i in range(3))
        scores = q @ k.transpose(-1, -2) / math.sqrt(dh) + bias
        out = (torch.softmax(scores, -1) @ v).transpose(1, 2).reshape(b, n, d)
        return self.proj(out)

    def forward(self, x, c, bias):
        s1, sc1, g1, s2, sc2, g2 = (m.unsqueeze(1) for m in self.modulation(c).chunk(6, dim=1))
        x = x + g1 * self.attention(modulate(layer_norm(x), s1, sc1), bias)
        h = self.fc2(F.silu(self.fc1(modulate(layer_norm(x), s2, sc2))))
        return x + g2 * h


class Denoiser(nn.Module):
    def __init__(self, token_dim=30, d=128, blocks=4, heads=4, ratio=4, width=64):
        super().__init__()
        self.d = d
        self.input = nn.Linear(token_dim, d)
        self.time0, self.time1 = nn.Linear(64, d), nn.Linear(d, d)
        self.contact0, self.contact1 = nn.Linear(11, d), nn.Linear(d, d)
        self.contact_kind = nn.Parameter(torch.randn(1, 1, d) * 0.02)
        self.floor, self.free = PointNet(4, width, d), PointNet(3, width, d)
        self.blocks = nn.ModuleList(Block(d, heads, ratio) for _ in range(blocks))
        self.final_modulation, self.output = nn.Linear(d, 2 * d), nn.Linear(d, token_dim)
        for layer in (self.final_modulation, self.output):
            nn.init.zeros_(layer.weight)
            nn.init.zeros_(layer.bias)

    def encode(self, contacts, mask, floor, free):
        """The step-independent part of forward: pooled contacts + PointNets, contact tokens, bias."""
        cont = self.contact1(F.silu(self.contact0(contacts)))
        m = mask.unsqueeze(2)
        pooled = (cont * m).sum(1) / (m.sum(1) + 1e-6)
        return pooled + self.floor(floor) + self.free(free), cont + self.contact_kind, mask

    def step(self, x, t, encoded):
        """forward() with the conditions encoded once by encode()."""
        static, tokens, mask = encoded
        b, slots, _ = x.shape
        half = 32
        freqs = torch.exp(-math.log(10000.0) * torch.arange(half) / half)
        angles = t[:, None].float() * freqs[None]
        time = self.time1(F.silu(self.time0(torch.cat([angles.sin(), angles.cos()], dim=1))))
        c = F.silu(time + static)
        h = torch.cat([self.input(x), tokens], dim=1)
        bias = ((torch.cat([torch.ones(b, slots), mask], dim=1) - 1) * 1e9).reshape(b, 1, 1, -1)
        for block in self.blocks:
            h = block(h, c, bias)
        h = h[:, :slots]
        shift, scale = (v.unsqueeze(1) for v in self.final_modulation(c).chunk(2, dim=1))
        return self.output(modulate(layer_norm(h), shift, scale))

    def forward(self, x, t, contacts, mask, floor, free):
        b, slots, _ = x.shape
        half = 32
        freqs = torch.exp(-math.log(10000.0) * torch.arange(half) / half)
        angles = t[:, None].float() * freqs[None]
        tf = torch.cat([angles.sin(), angles.cos()], dim=1)
        time = self.time1(F.silu(self.time0(tf)))
        cont = self.contact1(F.silu(self.contact0(contacts)))
        m = mask.unsqueeze(2)
        pooled = (cont * m).sum(1) / (m.sum(1) + 1e-6)
        c = F.silu(time + pooled + self.floor(floor) + self.free(free))
        h = torch.cat([self.input(x), cont + self.contact_kind], dim=1)
        visible = torch.cat([torch.ones(b, slots), mask], dim=1)
        bias = ((visible - 1) * 1e9).reshape(b, 1, 1, -1)
        for block in self.blocks:
            h = block(h, c, bias)
        h = h[:, :slots]
        shift, scale = (v.unsqueeze(1) for v in self.final_modulation(c).chunk(2, dim=1))
        return self.output(modulate(layer_norm(h), shift, scale))


def conditions(b, k=8, p=128, q=64):
    mask = torch.zeros(b, k)
    mask[:, :3] = 1
    return torch.randn(b, k, 11), mask, torch.randn(b, p, 4), torch.randn(b, q, 3)


def sample(model, b, slots=12, dim=30, steps=200, cached=False):
    betas = torch.linspace(1000 / steps * 1e-4, 1000 / steps * 0.02, steps, dtype=torch.float64)
    ab = torch.cumprod(1 - betas, 0)
    cond = conditions(b)
    x = torch.randn(b, slots, dim)
    with torch.no_grad():
        encoded = model.encode(*cond) if cached else None
        for t in reversed(range(steps)):
            tt = torch.full((b,), t)
            eps = model.step(x, tt, encoded) if cached else model(x, tt, *cond)
            a = ab[t].item()
            x0 = ((x - math.sqrt(1 - a) * eps) / math.sqrt(a)).clamp(-1, 1)
            prev = ab[t - 1].item() if t > 0 else 1.0
            beta = betas[t].item()
            c0 = beta * math.sqrt(prev) / (1 - a)
            ct = (1 - prev) * math.sqrt(1 - beta) / (1 - a)
            mean = c0 * x0 + ct * x
            x = mean + math.sqrt(beta * (1 - prev) / (1 - a)) * torch.randn_like(x) if t > 0 else mean
    return x


def train_step(model, opt, b, slots=12, dim=30):
    x0 = torch.randn(b, slots, dim)
    t = torch.randint(0, 200, (b,))
    noise = torch.randn_like(x0)
    pred = model(x0 + noise, t, *conditions(b))
    loss = ((pred - noise) ** 2).mean()
    opt.zero_grad()
    loss.backward()
    torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
    opt.step()


def best_seconds(f, repeats):
    f()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sample-batch", type=int, default=16)
    ap.add_argument("--train-batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    torch.set_num_threads(args.threads)
    torch.manual_seed(0)
    model = Denoiser()
    opt = torch.optim.AdamW(model.parameters(), lr=3e-4, weight_decay=0.0)
    sampling = best_seconds(lambda: sample(model, args.sample_batch), args.repeats)
    cached = best_seconds(lambda: sample(model, args.sample_batch, cached=True), args.repeats)
    step = best_seconds(lambda: [train_step(model, opt, args.train_batch) for _ in range(10)], args.repeats) / 10
    print(json.dumps({
        "torch": torch.__version__,
        "parameters": sum(p.numel() for p in model.parameters()),
        "sample_seconds": sampling,
        "sample_cached_seconds": cached,
        "train_step_seconds": step,
    }))


if __name__ == "__main__":
    main()
